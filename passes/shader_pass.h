// A pass of one shader, its resources listed once in binding order (binding i is the list's
// element i): the list gives the pipeline's descriptor layout, the pass's declarations to the
// frame graph (each resource with its usage) and, when the pass records, its descriptor set.
// addComputePass runs a compute shader over its first written image (or a given grid); a raster
// pass (the MSAA resolve) uses the bindings alone.
#pragma once

#include "gpu/frame_graph.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace obscura::passes {

enum class SampledRead { Nearest, Linear };

// One binding of a shader and the resource it is given. Depth images are sampled in the
// depth/stencil read-only layout, others in the shader read-only one.
struct ShaderBinding {
    enum class Kind {
        Unbound,           // a binding number this variant of the shader does not use
        Sampled,           // combined image sampler
        SampledStencil,    // the stencil aspect of a depth/stencil image
        StorageRead,       // storage image, imageLoad
        StorageWrite,      // storage image, imageStore (one mip level with `level`)
        StorageReadWrite,  // storage image read and written in place
        BufferRead,        // storage buffer
        BufferWrite,
        BufferReadWrite,   // storage buffer read and written (atomics)
    };
    Kind kind = Kind::Unbound;
    gpu::ImageHandle image;
    gpu::BufferHandle buffer;
    SampledRead read = SampledRead::Nearest;
    VkSampler sampler = VK_NULL_HANDLE;  // set: this sampler rather than a clamped one of `read`
    std::optional<uint32_t> level;
};

ShaderBinding sampled(gpu::ImageHandle image, SampledRead read = SampledRead::Nearest);
ShaderBinding sampled(gpu::ImageHandle image, VkSampler sampler);
ShaderBinding sampledStencil(gpu::ImageHandle depthStencil);
ShaderBinding storageRead(gpu::ImageHandle image);
ShaderBinding storageWrite(gpu::ImageHandle image);
ShaderBinding storageWriteLevel(gpu::ImageHandle image, uint32_t level);
ShaderBinding storageReadWrite(gpu::ImageHandle image);
ShaderBinding bufferRead(gpu::BufferHandle buffer);
ShaderBinding bufferWrite(gpu::BufferHandle buffer);
ShaderBinding bufferReadWrite(gpu::BufferHandle buffer);
ShaderBinding unbound();

// Where a pass's shaders run: the stages its reads are declared for (Graphics: vertex and
// fragment shaders).
enum class ShaderStage { Compute, Graphics };

// The descriptor layout the bindings make.
std::vector<gpu::BindingDesc> bindingLayout(const std::vector<ShaderBinding>& bindings);
// Declares every bound resource to the pass being set up, once per resource and usage.
void declareBindings(gpu::FrameGraph::PassBuilder& pass, const std::vector<ShaderBinding>& bindings,
                     ShaderStage stage);
// Writes the descriptor set of `pipeline` from the bindings and binds it.
void bindBindings(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, const std::vector<ShaderBinding>& bindings,
                  const gpu::PassResources& resources);

struct ComputePass {
    std::string shader;  // "dof_gather" runs shaders/dof_gather.comp and names its pipeline
    std::vector<ShaderBinding> bindings;
    std::vector<uint8_t> constants;  // push constants, in the shader's layout
    // Specialization constants: the pipeline is built (and cached) per distinct set.
    std::vector<gpu::SpecializationConstant> specialization;
    // The texels the dispatch covers: the first written image's size unless set.
    std::optional<std::array<uint32_t, 2>> texels;
    // Texels one workgroup covers (x, y): 8x8 for 8x8 groups of one invocation per texel, 1x1 for
    // a workgroup per texel (a tile reduced in shared memory).
    std::array<uint32_t, 2> texelsPerGroup{8, 8};
    std::string label;  // the pass's name in timings; the shader's name when empty
};

// The bytes of a struct mirrored in a shader (push constants, a constant buffer's contents).
template <typename T>
std::vector<uint8_t> bytesOf(const T& value) {
    const auto* bytes = reinterpret_cast<const uint8_t*>(&value);
    return {bytes, bytes + sizeof(T)};
}

// A 2D single-sample image (storage and sampled use come from the graph).
gpu::ImageDesc imageDesc2D(VkFormat format, uint32_t width, uint32_t height);

// What a pass wrote (the versions its writes made), in the order of its write bindings.
struct ComputeOutputs {
    std::vector<gpu::ImageHandle> images;
    std::vector<gpu::BufferHandle> buffers;
};

ComputeOutputs addComputePass(gpu::FrameGraph& graph, ComputePass pass);
// One pass of several dispatches of one shader, each with its own bindings and constants (one per
// AOV, one per mip level): one entry in the timings, every dispatch's resources declared once.
ComputeOutputs addComputeDispatches(gpu::FrameGraph& graph, const std::string& label,
                                    std::vector<ComputePass> dispatches);

}  // namespace obscura::passes
