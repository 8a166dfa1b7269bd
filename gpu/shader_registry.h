// SPIR-V modules compiled from shaders/ at build time register themselves here by file name
// (cmake/EmbedSpirv.cmake), so the plugin carries its shaders inside the library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace obscura::gpu {

struct ShaderRegistration {
    ShaderRegistration(const char* name, const std::uint32_t* words, std::size_t wordCount);
};

// The SPIR-V of a shader by file name ("lighting.comp"); empty if unknown.
std::span<const std::uint32_t> findShader(std::string_view name);

}  // namespace obscura::gpu
