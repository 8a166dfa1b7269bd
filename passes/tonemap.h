// Frame step 12: the exposed accumulation through the OCIO display/view transform (tone curve,
// gamut and encoding), baked into a 3D LUT behind a log2 shaper, to an 8-bit display image.
#pragma once

#include "pass_support/color_grading_lut.h"
#include "passes/frame_resources.h"
#include "passes/hdr_color.h"

namespace obscura::passes {

constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

// The display image's alpha is `hdrColor`'s alpha where that holds coverage, else `coverage`'s (the
// G-buffer's instance target: 1 where something drew) composited with `transparentCoverage`
// (passes/transparent.h).
gpu::ImageHandle addTonemapPass(gpu::FrameGraph& graph, const FrameScene& scene,
                                gpu::ImageHandle hdrColor, HdrAlpha hdrAlpha, gpu::ImageHandle coverage,
                                gpu::ImageHandle transparentCoverage, const ColorGradingLut& grading);

}  // namespace obscura::passes
