// G-buffer pass (frame step 4): rasterises every draw into the thin G-buffer of seed 004.
#pragma once

#include "gpu/frame_graph.h"
#include "passes/frame_resources.h"
#include "passes/frame_scene.h"

namespace obscura::passes {

// Draws every opaque draw of the scene (Draw::transparent ones are the transparent pass's). With
// more than one sample (render setting msaa) every target is multisampled; the custom resolve
// (msaa_resolve.h) turns it into the single-sample G-buffer the other passes read.
// Cut-out materials (opacityThreshold) cover the samples their opacity passes at each sample's
// position (alpha-test supersampling), or with `alphaToCoverage` the fraction of the samples their
// opacity gives (seed 000 "Deferred MSAA \ alpha test SSAA", "performance shortcuts (3)").
// Under GPU occlusion culling (`early`, passes/occlusion_cull.h) it draws the static draws, the
// culled ones' early instances among them; addGBufferLatePass then draws the rest.
GBuffer addGBufferPass(gpu::FrameGraph& graph, const FrameScene& scene,
                       gpu::ImageHandle bestFitNormals, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT,
                       bool alphaToCoverage = false, const CulledDraws* early = nullptr);

// GPU occlusion culling's second G-buffer pass, over what the first drew: the culled draws' late
// instances, then the moving draws (drawn last, as without culling).
GBuffer addGBufferLatePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& early,
                           gpu::ImageHandle bestFitNormals, VkSampleCountFlagBits samples, bool alphaToCoverage,
                           const CulledDraws& late);

}  // namespace obscura::passes
