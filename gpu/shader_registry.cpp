#include "gpu/shader_registry.h"

#include <map>
#include <string>

namespace obscura::gpu {
namespace {
// Function-local static: registrations run during static initialisation of other files.
std::map<std::string, std::span<const std::uint32_t>, std::less<>>& registry() {
    static std::map<std::string, std::span<const std::uint32_t>, std::less<>> shaders;
    return shaders;
}
}  // namespace

ShaderRegistration::ShaderRegistration(const char* name, const std::uint32_t* words, std::size_t wordCount) {
    registry().emplace(name, std::span<const std::uint32_t>(words, wordCount));
}

std::span<const std::uint32_t> findShader(std::string_view name) {
    auto it = registry().find(name);
    return it == registry().end() ? std::span<const std::uint32_t>{} : it->second;
}

}  // namespace obscura::gpu
