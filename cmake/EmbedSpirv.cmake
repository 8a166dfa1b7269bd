# Writes a SPIR-V binary as `extern const std::uint32_t <SYMBOL>[]` with its word count,
# registered in the shader registry (gpu/shader_registry.h) under the shader's file name.
file(READ ${INPUT} hex HEX)
string(LENGTH "${hex}" nchars)
math(EXPR nwords "${nchars} / 8")
string(REGEX MATCHALL "........" words "${hex}")
set(body "")
foreach(w IN LISTS words)
  # SPIR-V words are little-endian in the file.
  string(SUBSTRING ${w} 0 2 b0)
  string(SUBSTRING ${w} 2 2 b1)
  string(SUBSTRING ${w} 4 2 b2)
  string(SUBSTRING ${w} 6 2 b3)
  string(APPEND body "0x${b3}${b2}${b1}${b0}u,")
endforeach()
get_filename_component(name ${INPUT} NAME_WE)
get_filename_component(full ${INPUT} NAME)
string(REGEX REPLACE "\\.spv$" "" shader_name ${full})
file(WRITE ${OUTPUT} "// Generated from ${shader_name}; do not edit.\n#include \"gpu/shader_registry.h\"\nnamespace {\nconst std::uint32_t kWords[] = {${body}};\nconst obscura::gpu::ShaderRegistration kRegistration{\"${shader_name}\", kWords, ${nwords}};\n}\n")
