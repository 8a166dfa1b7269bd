# Warnings on and treated as errors for our own targets; sanitizers when asked.
# Missing field initializers are the Vulkan idiom `VkFooInfo info{VK_STRUCTURE_TYPE_FOO}`.
# -Wrestrict: GCC 12 reports false positives inside std::string at -O2 (GCC bug 105329).
function(obscura_target_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion -Wno-missing-field-initializers -Werror>
    $<$<AND:$<COMPILE_LANGUAGE:CXX>,$<CXX_COMPILER_ID:GNU>>:-Wno-restrict>
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic -Werror>)
endfunction()

if(OBSCURA_SANITIZE)
  # glslang is built without RTTI: the vptr check cannot work across it. -O1 after the build type's
  # flags (a Debug build keeps its assertions): AddressSanitizer's own advice, and unoptimised code
  # would make every test process spend a minute baking the best-fit normals table. GCC 12's
  # -Wmaybe-uninitialized reports false positives with -fsanitize=address at -O1 (inside std::regex's
  # std::function members), so it is off in this build only.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize=vptr -fno-omit-frame-pointer -fno-sanitize-recover=undefined
                      -O1 -Wno-maybe-uninitialized)
  add_link_options(-fsanitize=address,undefined)
endif()
