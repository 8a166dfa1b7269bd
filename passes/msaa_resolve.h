// Deferred MSAA custom resolve (frame step 5; seed 000 "Deferred MSAA \ custom resolve &
// per-sample mask" and "stencil batching"): after a multisampled G-buffer, one raster pass copies
// sample 0 of every target into a single-sample G-buffer for the pixel-frequency passes and tags
// the 2x2 quads whose samples differ in the reserved stencil bit of that G-buffer's stencil.
#pragma once

#include "passes/gbuffer.h"

namespace obscura::passes {

// Mirrors shaders/common/msaa_samples.glsl MSAA_EDGE_STENCIL_BIT; clip volumes own 0x01..0x40.
constexpr uint32_t kMsaaEdgeStencilBit = 0x80;

// `multisampled` comes from addGBufferPass with more than one sample. The returned G-buffer has
// one sample per pixel, sample 0's values, depth/stencil cleared to (sample 0's depth, 0) with the
// edge bit set where the lighting must work per sample.
GBuffer addMsaaResolvePass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                           const GBuffer& multisampled);

}  // namespace obscura::passes
