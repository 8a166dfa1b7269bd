// Transparent surfaces (frame step 8, DESIGN.md "The frame"): a forward raster pass after deferred
// lighting that draws FrameScene::transparentDraws back to front into the light accumulation,
// lit by every light, its shadows and the dome, blended "over" with premultiplied colour
// (shaders/transparent.frag).
#pragma once

#include "passes/frame_resources.h"

namespace obscura::passes {

// What the transparent surfaces leave in a pixel, "over" the opaque surfaces and the background:
// 1 - prod(1 - opacity_i); the colour AOV's alpha composites it with the G-buffer's coverage
// (shaders/common/coverage.glsl).
constexpr VkFormat kTransparentCoverageFormat = VK_FORMAT_R8_UNORM;

struct TransparentSettings {
    // Soft-particle fade (render setting transparents:fadeDistance, scene units): a surface fades
    // out over this distance in front of the opaque surface behind it; 0: a hard intersection.
    float fadeDistance = 0.0f;
};

// `draws` are the transparent draws to render, back to front (FrameScene::transparentDraws).
// `opaqueDepth` is the depth transparents are tested against and fade with (sampled, no depth
// attachment): the G-buffer's depth, or with a multisampled G-buffer the max of its samples (seed
// 000 "Deferred MSAA \ performance shortcuts (2)"). `hdr` is the light accumulation, blended
// into in place. `draws` is not empty: a frame without transparent surfaces runs no pass, and its
// coverage is one texel of 0 (transparentCoverageAt, shaders/common/coverage.glsl).
// The frame's colour with the transparent surfaces over it, and their coverage.
struct TransparentResult {
    gpu::ImageHandle hdr;
    gpu::ImageHandle coverage;  // kTransparentCoverageFormat
};

TransparentResult addTransparentPass(gpu::FrameGraph& graph, const FrameScene& scene,
                                    const std::vector<uint32_t>& draws, gpu::ImageHandle opaqueDepth,
                                    gpu::ImageHandle hdr, gpu::ImageHandle shadowAtlas,
                                    const EnvironmentLighting& environment, const TransparentSettings& settings);

}  // namespace obscura::passes
