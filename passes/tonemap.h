// Frame step 12: the exposed accumulation through the OCIO display/view transform (tone curve,
// gamut and encoding), baked into a 3D LUT behind a log2 shaper, to an 8-bit display image.
#pragma once

#include "passes/color_grading_lut.h"
#include "passes/gbuffer.h"

namespace obscura::passes {

constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

gpu::ImageHandle addTonemapPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                gpu::ImageHandle hdrColor, gpu::ImageHandle coverage, const ColorGradingLut& grading);

}  // namespace obscura::passes
