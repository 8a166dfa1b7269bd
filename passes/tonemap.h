// Exposure is applied in the accumulation; this pass (frame step 12) tone maps to an 8-bit
// display image.
#pragma once

#include "passes/gbuffer.h"

namespace obscura::passes {

constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

gpu::ImageHandle addTonemapPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                gpu::ImageHandle hdrColor, gpu::ImageHandle coverage);

}  // namespace obscura::passes
