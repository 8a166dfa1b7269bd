# GLSL -> SPIR-V at build time with glslangValidator, then embedded as C++ arrays so the plugin
# is a single file that needs no shader folder at run time.
set(OBSCURA_SHADER_DIR ${CMAKE_SOURCE_DIR}/shaders)

# obscura_add_shaders(TARGET <lib> SHADERS a.comp b.vert ...)
function(obscura_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SHADERS" ${ARGN})
  set(gen_dir ${CMAKE_BINARY_DIR}/generated/shaders)
  file(MAKE_DIRECTORY ${gen_dir})
  set(sources)
  foreach(shader IN LISTS ARG_SHADERS)
    get_filename_component(name ${shader} NAME)
    string(MAKE_C_IDENTIFIER ${name} ident)
    set(spv ${gen_dir}/${name}.spv)
    set(cpp ${gen_dir}/${name}.spv.cpp)
    add_custom_command(
      OUTPUT ${spv}
      COMMAND Vulkan::glslangValidator -V --target-env vulkan1.3 -I${OBSCURA_SHADER_DIR}
              --depfile ${spv}.d -o ${spv} ${OBSCURA_SHADER_DIR}/${shader}
      DEPENDS ${OBSCURA_SHADER_DIR}/${shader}
      DEPFILE ${spv}.d
      COMMENT "glslang ${shader}"
      VERBATIM)
    add_custom_command(
      OUTPUT ${cpp}
      COMMAND ${CMAKE_COMMAND} -DINPUT=${spv} -DOUTPUT=${cpp} -DSYMBOL=${ident}
              -P ${CMAKE_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      DEPENDS ${spv} ${CMAKE_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      VERBATIM)
    list(APPEND sources ${cpp})
  endforeach()
  target_sources(${ARG_TARGET} PRIVATE ${sources})
endfunction()
