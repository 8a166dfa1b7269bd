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
  set_property(GLOBAL APPEND PROPERTY OBSCURA_SHADER_MODULES ${spv})
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

# generated/shader_layouts.h: the byte offset of every member of every struct and block of the
# shaders compiled so far, read from their SPIR-V (cmake/generate_shader_layouts.cpp), for the
# static_asserts of the C++ structs that mirror them. `target` (which holds those structs) is built
# after it and includes it as "generated/shader_layouts.h".
function(obscura_add_shader_layouts target)
  get_property(modules GLOBAL PROPERTY OBSCURA_SHADER_MODULES)
  set(header ${CMAKE_BINARY_DIR}/generated/include/generated/shader_layouts.h)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/generated/include/generated)
  add_executable(obscura_generate_shader_layouts ${CMAKE_SOURCE_DIR}/cmake/generate_shader_layouts.cpp)
  obscura_target_warnings(obscura_generate_shader_layouts)
  add_custom_command(
    OUTPUT ${header}
    COMMAND obscura_generate_shader_layouts ${header} ${modules}
    DEPENDS obscura_generate_shader_layouts ${modules}
    COMMENT "Reading the shaders' struct layouts"
    VERBATIM)
  add_custom_target(obscura_shader_layouts DEPENDS ${header})
  add_dependencies(${target} obscura_shader_layouts)
  target_include_directories(${target} PUBLIC ${CMAKE_BINARY_DIR}/generated/include)
endfunction()
