#include "delegate/colour_block_compression.h"

#include <squish.h>

#include <cstdint>

namespace obscura::delegate {
namespace {

bool isBc1(VkFormat format) { return format == VK_FORMAT_BC1_RGB_SRGB_BLOCK || format == VK_FORMAT_BC1_RGB_UNORM_BLOCK; }

}  // namespace

VkFormat colourBlockFormat(const gpu::MipLevel& rgba8, VkFormat uncompressed) {
    bool opaque = true;
    for (size_t i = 3; i < rgba8.bytes.size() && opaque; i += 4) opaque = rgba8.bytes[i] == std::byte{255};
    const bool srgb = uncompressed == VK_FORMAT_R8G8B8A8_SRGB;
    if (opaque) return srgb ? VK_FORMAT_BC1_RGB_SRGB_BLOCK : VK_FORMAT_BC1_RGB_UNORM_BLOCK;
    return srgb ? VK_FORMAT_BC3_SRGB_BLOCK : VK_FORMAT_BC3_UNORM_BLOCK;
}

gpu::MipLevel compressColourLevel(const gpu::MipLevel& rgba8, VkFormat blockFormat) {
    const int flags = (isBc1(blockFormat) ? squish::kDxt1 : squish::kDxt5) | squish::kColourClusterFit;
    const int width = int(rgba8.width), height = int(rgba8.height);
    gpu::MipLevel out{rgba8.width, rgba8.height,
                      std::vector<std::byte>(size_t(squish::GetStorageRequirements(width, height, flags)))};
    squish::CompressImage(reinterpret_cast<const squish::u8*>(rgba8.bytes.data()), width, height, out.bytes.data(),
                          flags);
    return out;
}

}  // namespace obscura::delegate
