// BC1 and BC3 block compression of 8-bit colour textures through libsquish (seed 004's agenda,
// "Improvements to the DXT block compression"): BC1 (4 bits per texel) where every texel is
// opaque, BC3 (8 bits, alpha in its own BC4-like block) otherwise, in the texture's own space (sRGB
// codes for sRGB textures: the sampler decodes after the block decode, so the encoder's error is
// spread evenly in perceptual terms). Pure CPU code.
#pragma once

#include "gpu/texture_upload.h"

#include <vulkan/vulkan.h>

namespace obscura::delegate {

// The block format of an R8G8B8A8_SRGB or R8G8B8A8_UNORM image: BC1_RGB for opaque texels, BC3
// when any texel's alpha is below 1.
VkFormat colourBlockFormat(const gpu::MipLevel& rgba8, VkFormat uncompressed);

// `rgba8` compressed as `blockFormat` (squish's cluster fit, uniform channel weights).
gpu::MipLevel compressColourLevel(const gpu::MipLevel& rgba8, VkFormat blockFormat);

}  // namespace obscura::delegate
