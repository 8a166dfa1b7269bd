// Texture files decoded for the GPU from their bytes in memory, pure CPU code: 8-bit images (PNG,
// JPEG, TGA, BMP, ... through stb_image) become RGBA8, sRGB-encoded or linear; 16-bit PNGs of
// material inputs keep their precision through histogram renormalisation
// (texture_renormalization.h); float images (Radiance HDR through stb_image, OpenEXR) become
// RGBA16F. Also the CPU mip filter for formats the GPU cannot blit.
#pragma once

#include "gpu/texture_upload.h"

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace obscura::delegate {

// UsdUVTexture inputs:sourceColorSpace.
enum class SourceColorSpace { Auto, Srgb, Raw };
SourceColorSpace parseSourceColorSpace(const std::string& token);

// The reason stb_image gave for its last failure on this thread.
std::string stbFailureReason();

// A file's bytes as stb_image's readers take them, with an int length: nullopt from 2 GiB on.
struct StbBytes {
    const unsigned char* data = nullptr;
    int size = 0;
    static std::optional<StbBytes> of(std::string_view bytes);
    static constexpr const char* kTooLarge = "the file is too large to decode (2 GiB or more)";
};

// Whether `bytes` are an OpenEXR file (its magic number).
bool isOpenExr(std::string_view bytes);

// What a texture feeds, which decides how it may be stored.
enum class TextureRole {
    Plain,     // sampled as it is (dome lights): texels keep their values
    Material,  // a UsdUVTexture output, whose scale and bias can absorb a renormalisation
    // A tangent-space normal map read as +-(2 texel - 1) per channel: stored in two channels with
    // z reconstructed (normal_map_image.h) where the file is 16-bit or BC5 can hold it, else (a
    // float file too) as its RGBA texels.
    Normal,
};

struct TextureImage {
    VkFormat format = VK_FORMAT_UNDEFINED;  // R8G8B8A8_SRGB, R8G8B8A8_UNORM or R16G16B16A16_SFLOAT
    gpu::MipLevel level0;
    // Mean RGBA of what a sampler returns (linear values: sRGB texels are decoded first), the
    // value of the 1x1 mip of an ideal box-filtered chain.
    std::array<float, 4> average{};
    // Per channel, what the sampled value maps to: value * renormScale + renormBias (identity
    // unless the texels were stretched by histogram renormalisation).
    std::array<float, 4> renormScale{1.0f, 1.0f, 1.0f, 1.0f};
    std::array<float, 4> renormBias{};
    bool renormalised() const { return renormScale != TextureImage{}.renormScale || renormBias != TextureImage{}.renormBias; }
};

// Decodes an image file's bytes. sRGB decoding applies to 8-bit files only: Srgb always, Auto for
// files of 3 or 4 channels (grey and grey+alpha stay linear, as OpenUSD's HioImage decides for
// "auto"); float files are linear whatever is asked. 16-bit PNGs of the Material role are
// renormalised where that is at least as precise as 8-bit storage; other 16-bit PNGs are reduced to
// 8 bits. Returns the reason when the bytes cannot be decoded.
std::variant<TextureImage, std::string> decodeTextureImage(std::string_view bytes, SourceColorSpace colorSpace,
                                                           TextureRole role);

// The next mip level of `level` (a 2x2 box, in linear space for sRGB formats; an odd last row or
// column is dropped, a side of 1 stays 1).
gpu::MipLevel downsample(const gpu::MipLevel& level, VkFormat format);

// The chain of an 8-bit sRGB texture that is filtered in its encoded values and decoded after
// (R8G8B8A8_SRGB, read through its UNORM twin): level 0 as it is, and below it `levels` - 1 levels
// whose texels are area means, in linear light, of level 0's reconstruction over their footprints
// — decode(bilinear of the bytes), as Cycles reconstructs byte textures — so that a minified
// texture keeps what the path-traced pixel integrates even where neighbouring texels differ
// strongly (the mean of the decoded texels makes a one-texel black-and-white checker 0.5 grey;
// the reconstruction integrates to 0.246). Each level-0 texel's square is integrated at 4 x 4
// points (0.2408 for 0.2432 on a 30/230 checker), coarser levels are 2x2 boxes of those means (an
// odd last row or column dropped, as downsample()); alpha is a plain box. The reconstruction is
// clamped at the borders of `cellWidth` x `cellHeight` cells (a UDIM atlas's tiles; 0: the image).
std::vector<gpu::MipLevel> encodedReconstructionMips(gpu::MipLevel level0, uint32_t levels, uint32_t cellWidth = 0,
                                                     uint32_t cellHeight = 0);

// `level` at width x height (in linear space for sRGB formats): halved by `downsample` while it is
// at least twice as large, then filtered bilinearly, texel centres to texel centres.
gpu::MipLevel resample(const gpu::MipLevel& level, VkFormat format, uint32_t width, uint32_t height);

// Bytes of one texel of an uncompressed format TextureImage holds.
size_t bytesPerTexel(VkFormat format);

}  // namespace obscura::delegate
