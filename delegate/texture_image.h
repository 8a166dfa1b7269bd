// Texture files decoded for the GPU, pure CPU code: 8-bit images (PNG, JPEG, TGA, BMP, ...
// through stb_image) become RGBA8, sRGB-encoded or linear; 16-bit PNGs of material inputs keep
// their precision through histogram renormalisation (texture_renormalization.h); float images
// (Radiance HDR through stb_image, OpenEXR) become RGBA16F. Also the CPU mip filter for formats
// the GPU cannot blit.
#pragma once

#include "gpu/texture_upload.h"

#include <array>
#include <string>
#include <variant>

namespace obscura::delegate {

// UsdUVTexture inputs:sourceColorSpace.
enum class SourceColorSpace { Auto, Srgb, Raw };
SourceColorSpace parseSourceColorSpace(const std::string& token);

// The reason stb_image gave for its last failure on this thread.
std::string stbFailureReason();

// What a texture feeds, which decides how it may be stored.
enum class TextureRole {
    Plain,     // sampled as it is (dome lights): texels keep their values
    Material,  // a UsdUVTexture output, whose scale and bias can absorb a renormalisation
    // A tangent-space normal map read as +-(2 texel - 1) per channel: stored in two channels with
    // z reconstructed (normal_map_image.h) where the file is 16-bit or BC5 can hold it, else as
    // Material.
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

// Reads an image file. sRGB decoding applies to 8-bit files only: Srgb always, Auto for files of
// 3 or 4 channels (grey and grey+alpha stay linear, as OpenUSD's HioImage decides for "auto");
// float files are linear whatever is asked. 16-bit PNGs of the Material role are renormalised where
// that is at least as precise as 8-bit storage; other 16-bit PNGs are reduced to 8 bits. Returns
// the reason when the file cannot be read.
std::variant<TextureImage, std::string> decodeTextureFile(const std::string& path, SourceColorSpace colorSpace,
                                                          TextureRole role);

// The next mip level of `level` (a 2x2 box, in linear space for sRGB formats; an odd last row or
// column is dropped, a side of 1 stays 1).
gpu::MipLevel downsample(const gpu::MipLevel& level, VkFormat format);

// `level` at width x height (in linear space for sRGB formats): halved by `downsample` while it is
// at least twice as large, then filtered bilinearly, texel centres to texel centres.
gpu::MipLevel resample(const gpu::MipLevel& level, VkFormat format, uint32_t width, uint32_t height);

// Bytes of one texel of an uncompressed format TextureImage holds.
size_t bytesPerTexel(VkFormat format);

}  // namespace obscura::delegate
