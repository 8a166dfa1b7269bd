// A transfer pass copying one buffer into another (the first `bytes` of it, or the whole source):
// GPU occlusion culling's commands start each frame from the host's and go back to it once the
// frame ran, while the GPU counts into device-local memory.
#pragma once

#include "gpu/frame_graph.h"

#include <string>

namespace obscura::passes {

// Returns the version of `destination` the copy writes.
gpu::BufferHandle addBufferCopyPass(gpu::FrameGraph& graph, const std::string& name, gpu::BufferHandle source,
                                    gpu::BufferHandle destination, VkDeviceSize bytes);

}  // namespace obscura::passes
