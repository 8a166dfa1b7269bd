// Screen-space ambient occlusion (seed 004 "SSAO improvements"): volumetric obscurance (Loos &
// Sloan 2010) with 4 samples per pixel at half resolution, then a bilateral blur that keeps depth
// edges. The lighting pass upsamples the result with sampleAmbientAccess()
// (shaders/common/ssao_upsample.glsl).
#pragma once

#include "passes/gbuffer.h"

namespace obscura::passes {

// Linear view depth (distance along the view axis) at half resolution. Seed 004 packs depth into
// two 8-bit channels beside the AO so that the blur fetches both at once; a [0, 1] fixed-point
// encoding over USD's default clipping range (1 to 1e6) is far too coarse for depths compared to a
// fraction of the sampling radius, so depth keeps 32-bit float and the blur fetches twice.
constexpr VkFormat kSsaoDepthFormat = VK_FORMAT_R32_SFLOAT;
// Ambient accessibility, 1 = unoccluded.
constexpr VkFormat kSsaoAccessibilityFormat = VK_FORMAT_R8_UNORM;

struct SsaoSettings {
    float radius = 0.5f;     // of the sampling sphere, in scene units
    float intensity = 1.0f;  // scales the occlusion: accessibility = 1 - intensity * occlusion
};

// Both images are ceil(width / 2) x ceil(height / 2): half-resolution texel (x, y) covers
// full-resolution pixels (2x..2x+1, 2y..2y+1).
struct SsaoResult {
    gpu::ImageHandle accessibility;  // kSsaoAccessibilityFormat
    gpu::ImageHandle halfDepth;      // kSsaoDepthFormat, the depths the accessibility belongs to
};

SsaoResult addSsaoPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                         const GBuffer& gbuffer, const SsaoSettings& settings);

}  // namespace obscura::passes
