// Tangent-space normal maps stored in two channels, z reconstructed by the shader (Kaplanyan
// 2010, "Normal maps precision" and "3Dc encoder improvements"): decoding of 8- and 16-bit files
// to unit normals, their mip chain and the two-channel texel layouts. Pure CPU code.
#pragma once

#include "delegate/bc5_encoder.h"
#include "gpu/texture_upload.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace obscura::delegate {

struct NormalMapSource {
    NormalImage normals;  // normalize(2 texel - 1) of the file's RGB, (0, 0, 1) where that is 0
    bool sixteenBit = false;
};

// Whether stb_image reads the file's bytes as 8 or 16 bits per channel (not a float format).
bool isIntegerImage(std::string_view bytes);

// Whether stb_image reads the file's bytes as 16 bits per channel.
bool isSixteenBitImage(std::string_view bytes);

// The width and height in the file's header, without decoding its texels; nullopt where stb_image
// cannot read the header.
std::optional<std::array<uint32_t, 2>> imageExtent(std::string_view bytes);

// A file's bytes decoded; the reason when they cannot be.
std::variant<NormalMapSource, std::string> decodeNormalMap(std::string_view bytes);

// The next mip level: each texel the normalised mean of a 2x2 box (as downsample() crops).
NormalImage downsampleNormals(const NormalImage& level);

// x and y as 0.5 n + 0.5 in R16G16_UNORM or R8G8_UNORM texels.
gpu::MipLevel packTwoChannels(const NormalImage& level, VkFormat format);

}  // namespace obscura::delegate
