# GLSL -> SPIR-V at build time with glslangValidator, then embedded as C++ arrays so the plugin
# is a single file that needs no shader folder at run time.
set(OBSCURA_SHADER_DIR ${CMAKE_SOURCE_DIR}/shaders)

# One module: shaders/<source> compiled with -D<define> for each of `defines`, registered as <name>.
function(obscura_compile_shader target name source defines)
  set(gen_dir ${CMAKE_BINARY_DIR}/generated/shaders)
  file(MAKE_DIRECTORY ${gen_dir})
  string(MAKE_C_IDENTIFIER ${name} ident)
  set(spv ${gen_dir}/${name}.spv)
  set(cpp ${gen_dir}/${name}.spv.cpp)
  set(define_flags)
  foreach(define IN LISTS defines)
    list(APPEND define_flags -D${define})
  endforeach()
  add_custom_command(
    OUTPUT ${spv}
    COMMAND Vulkan::glslangValidator -V --target-env vulkan1.3 -I${OBSCURA_SHADER_DIR} ${define_flags}
            --depfile ${spv}.d -o ${spv} ${OBSCURA_SHADER_DIR}/${source}
    DEPENDS ${OBSCURA_SHADER_DIR}/${source}
    DEPFILE ${spv}.d
    COMMENT "glslang ${name}"
    VERBATIM)
  add_custom_command(
    OUTPUT ${cpp}
    COMMAND ${CMAKE_COMMAND} -DINPUT=${spv} -DOUTPUT=${cpp} -DSYMBOL=${ident}
            -P ${CMAKE_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    DEPENDS ${spv} ${CMAKE_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    VERBATIM)
  target_sources(${target} PRIVATE ${cpp})
endfunction()

# obscura_add_shaders(TARGET <lib> SHADERS a.comp b.vert ...)
function(obscura_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SHADERS" ${ARGN})
  foreach(shader IN LISTS ARG_SHADERS)
    get_filename_component(name ${shader} NAME)
    obscura_compile_shader(${ARG_TARGET} ${name} ${shader} "")
  endforeach()
endfunction()

# A permutation (STYLE.md "variants from options"): shaders/<SOURCE> built with the preprocessor
# DEFINES and registered under NAME.
# obscura_add_shader_variant(TARGET <lib> NAME x_variant.comp SOURCE x.comp DEFINES A B)
function(obscura_add_shader_variant)
  cmake_parse_arguments(ARG "" "TARGET;NAME;SOURCE" "DEFINES" ${ARGN})
  obscura_compile_shader(${ARG_TARGET} ${ARG_NAME} ${ARG_SOURCE} "${ARG_DEFINES}")
endfunction()
