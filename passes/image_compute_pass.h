// A compute pass of the post-processing chains (depth of field, motion blur): sampled images in,
// storage images out, one set of push constants, and optionally the frame's camera constants.
// The pipeline is named after its shader; its bindings follow the call's order: the inputs
// (0..n-1), then the outputs, then the camera uniform, then the storage buffers.
#pragma once

#include "gpu/frame_graph.h"
#include "passes/pipeline_cache.h"

#include <string>
#include <vector>

namespace obscura::passes {

enum class SampledRead { Nearest, Linear, Depth };

struct SampledInput {
    gpu::ImageHandle image;
    SampledRead read;
};

struct ImageComputePass {
    std::string shader;  // "dof_gather" runs shaders/dof_gather.comp
    std::vector<SampledInput> inputs;
    std::vector<gpu::ImageHandle> outputs;
    std::vector<uint8_t> constants;  // push constants, the shader's layout
    VkBuffer camera = VK_NULL_HANDLE;  // CameraData uniform, bound after the outputs when set
    std::vector<VkBuffer> storageBuffers;  // read-only records (e.g. the frame's InstanceData), bound last
    // Texels of the first output one workgroup covers per side: 8 for 8x8 groups of one
    // invocation per texel, 1 for a workgroup per texel (a tile reduced in shared memory).
    uint32_t texelsPerGroup = 8;
    std::string label;  // the pass's name in timings; the shader's name when empty
};

// A 2D single-sample image of the chain (storage and sampled use come from the graph).
gpu::ImageDesc chainImage(VkFormat format, uint32_t width, uint32_t height);

template <typename T>
std::vector<uint8_t> pushConstantBytes(const T& constants) {
    const auto* bytes = reinterpret_cast<const uint8_t*>(&constants);
    return {bytes, bytes + sizeof(T)};
}

void addImageComputePass(gpu::FrameGraph& graph, PipelineCache& pipelines, ImageComputePass pass);

}  // namespace obscura::passes
