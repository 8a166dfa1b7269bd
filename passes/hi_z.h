// GPU occlusion culling's depth pyramid (Hi-Z; shaders/common/hi_z.glsl): the depth the early
// G-buffer pass wrote reduced, level by level, to the farthest depth of ever larger squares of
// pixels, so that a box of any screen size is tested against it in four reads
// (shaders/occlusion_cull.comp).
#pragma once

#include "gpu/frame_graph.h"

#include <cstdint>
#include <string>

namespace obscura::passes {

// The floats of the pyramid of a `width` x `height` depth: levels 1 up to the single texel.
uint64_t hiZPyramidFloats(uint32_t width, uint32_t height);

// Reduces `depth` (the G-buffer's depth, single-sample or multisampled, or the shadow atlas) into
// `pyramid`, a buffer of hiZPyramidFloats() floats; returns its written version. The passes are
// named `label` and `label`_top.
gpu::BufferHandle addHiZPasses(gpu::FrameGraph& graph, gpu::ImageHandle depth, gpu::BufferHandle pyramid,
                               const std::string& label = "hi_z");

}  // namespace obscura::passes
