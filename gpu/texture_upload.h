// Sampled textures with a full mip chain: the levels the caller has are uploaded, the rest are
// made on the GPU by linear-filtered blits, each level from the one above it.
#pragma once

#include "gpu/device.h"

#include <cstddef>
#include <vector>

namespace obscura::gpu {

// One mip level, texels tightly packed, rows top first.
struct MipLevel {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<std::byte> bytes;
};

// floor(log2(max(width, height))) + 1: down to 1x1.
uint32_t mipLevelCount(uint32_t width, uint32_t height);

// Whether blits can make mips of `format`: optimal tiling supports BLIT_SRC, BLIT_DST and
// linear filtering of sampled images (vkCmdBlitImage with VK_FILTER_LINEAR requires all three).
bool canBlitMips(Device& device, VkFormat format);

// Creates a sampled image of desc.mipLevels levels from `levels` (level 0 first, at least one)
// and blits the levels not given; leaves every level SHADER_READ_ONLY_OPTIMAL. Blitting needs
// canBlitMips(desc.format). One submission, waited for.
ImagePtr createMipmappedTexture(Device& device, const ImageDesc& desc, const std::vector<MipLevel>& levels,
                                const char* debugName);

}  // namespace obscura::gpu
