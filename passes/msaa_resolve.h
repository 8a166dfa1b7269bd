// Deferred MSAA custom resolve (frame step 5; seed 000 "Deferred MSAA \ custom resolve &
// per-sample mask" and "stencil batching"): after a multisampled G-buffer, a compute pass copies
// sample 0 of every target it can write into a single-sample G-buffer for the pixel-frequency
// passes, chooses each pixel's depth and finds the 2x2 quads whose samples differ, tagging them
// with the reserved stencil bit in an R8 UINT stencil image. Only clip volumes, which rasterise
// against the depth and mark the stencil, need a depth/stencil target: for them a raster pass
// copies the depth and the tagged quads into one.
#pragma once

#include "passes/frame_resources.h"

namespace obscura::passes {

// Mirrors shaders/common/msaa_samples.glsl MSAA_EDGE_STENCIL_BIT; clip volumes own 0x01..0x40.
constexpr uint32_t kMsaaEdgeStencilBit = 0x80;
constexpr VkFormat kMaxDepthFormat = VK_FORMAT_R32_SFLOAT;

struct MsaaResolve {
    // One sample per pixel: sample 0's values (the centre's depth where the samples agree), the
    // stencil 0 with the edge bit set where the lighting must work per sample: in `stencil` (depth
    // R32 SFLOAT), or with clip volumes in the depth/stencil target `depth`.
    GBuffer resolved;
    // R32 SFLOAT: the farthest of each pixel's sample depths, for passes that test or fade against
    // the opaque depth without working per sample (seed 000 "Deferred MSAA \ performance shortcuts
    // (2)": "using max depth works ok for most cases and N-times faster"): the transparents.
    gpu::ImageHandle maxDepth;
};

// `multisampled` comes from addGBufferPass with more than one sample (its velocity target, if
// any, is resolved too).
MsaaResolve addMsaaResolvePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& multisampled);

}  // namespace obscura::passes
