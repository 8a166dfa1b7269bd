// Reference mode (DESIGN.md "Testing and measuring"; `obscura render --reference N`): the light
// accumulation of N sub-frames, each seen from another point of the lens, time of the shutter and
// sub-pixel position, summed with weights in linear HDR (the classic accumulation-buffer camera),
// then averaged into the format tone mapping reads.
#pragma once

#include "passes/frame_resources.h"

namespace obscura::passes {

// Sums of many sub-frames need more precision than the light accumulation format.
constexpr VkFormat kAccumulationFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

// accumulation = (first ? 0 : accumulation) + weight * (hdrColor, 1). `accumulation` is a persistent
// image of kAccumulationFormat, the size of the frame (FrameGraph::importPersistent), which the
// next sub-frame's graph reads; alpha sums the weights. `hdrColor` may hold a border of
// `guardPixels` around the frame (renderer::FrameViewpoint::guardPixels), which is left out.
void addAccumulatePass(gpu::FrameGraph& graph, gpu::ImageHandle hdrColor, gpu::ImageHandle accumulation, float weight,
                       bool first, uint32_t guardPixels = 0);

// The weighted mean, accumulation.rgb / accumulation.a, into a new image of `format` (the light
// accumulation's).
gpu::ImageHandle addAccumulationResolvePass(gpu::FrameGraph& graph, gpu::ImageHandle accumulation, VkFormat format);

}  // namespace obscura::passes
