// Deferred lighting (frame step 7, pixel frequency): a compute pass over the G-buffer that
// writes the light accumulation buffer.
#pragma once

#include "passes/gbuffer.h"
#include "passes/ssao.h"

namespace obscura::passes {

constexpr VkFormat kLightAccumulationFormat = VK_FORMAT_B10G11R11_UFLOAT_PACK32;

// `ambient` is the SSAO result (ssao.h), applied to environment (dome) light only, as seed 004
// asks of ambient occlusion. `shadowAtlas` is the shadow-map pass's atlas (shadow_maps.h),
// filtered per pixel for each light with shadow views (FrameScene::shadows).
gpu::ImageHandle addLightingPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                 const GBuffer& gbuffer, const SsaoResult& ambient, gpu::ImageHandle shadowAtlas);

}  // namespace obscura::passes
