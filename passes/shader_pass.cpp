#include "passes/shader_pass.h"

#include "gpu/vulkan_functions.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace obscura::passes {
namespace {

using Kind = ShaderBinding::Kind;

VkDescriptorType descriptorType(Kind kind) {
    switch (kind) {
        case Kind::Sampled:
        case Kind::SampledStencil: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        case Kind::StorageRead:
        case Kind::StorageWrite:
        case Kind::StorageReadWrite: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        case Kind::BufferRead:
        case Kind::BufferWrite:
        case Kind::BufferReadWrite: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        case Kind::Unbound: break;
    }
    throw std::logic_error("shader pass: an unbound binding has no descriptor type");
}

// The usages a binding declares: reads, then writes.
std::vector<gpu::Usage> usagesOf(Kind kind, ShaderStage stage) {
    const bool compute = stage == ShaderStage::Compute;
    switch (kind) {
        case Kind::Sampled:
        case Kind::SampledStencil:
            return {compute ? gpu::Usage::SampledCompute : gpu::Usage::SampledFragment};
        case Kind::BufferRead:
            return {compute ? gpu::Usage::StorageBufferRead : gpu::Usage::StorageBufferReadGraphics};
        case Kind::Unbound: return {};
        default: break;
    }
    if (!compute) throw std::logic_error("shader pass: storage resources are written by compute shaders only");
    switch (kind) {
        case Kind::StorageRead: return {gpu::Usage::StorageImageRead};
        case Kind::StorageWrite: return {gpu::Usage::StorageImageWrite};
        case Kind::StorageReadWrite: return {gpu::Usage::StorageImageRead, gpu::Usage::StorageImageWrite};
        case Kind::BufferWrite: return {gpu::Usage::StorageBufferWrite};
        case Kind::BufferReadWrite: return {gpu::Usage::StorageBufferRead, gpu::Usage::StorageBufferWrite};
        default: return {};
    }
}

bool isImage(Kind kind) {
    return kind == Kind::Sampled || kind == Kind::SampledStencil || kind == Kind::StorageRead ||
           kind == Kind::StorageWrite || kind == Kind::StorageReadWrite;
}

// Declares the bindings of every dispatch, each resource and usage once; returns what they write.
ComputeOutputs declare(gpu::FrameGraph::PassBuilder& pass, const std::vector<const std::vector<ShaderBinding>*>& lists,
                       ShaderStage stage) {
    std::vector<std::pair<uint64_t, gpu::Usage>> declared;
    ComputeOutputs outputs;
    for (const auto* bindings : lists)
        for (const ShaderBinding& b : *bindings) {
            const bool image = isImage(b.kind);
            const uint64_t resource = (uint64_t(image) << 32) | (image ? b.image.index : b.buffer.index);
            for (gpu::Usage usage : usagesOf(b.kind, stage)) {
                if (std::find(declared.begin(), declared.end(), std::pair{resource, usage}) != declared.end())
                    continue;
                declared.emplace_back(resource, usage);
                if (!gpu::isWrite(usage)) {
                    if (image) pass.read(b.image, usage);
                    else pass.read(b.buffer, usage);
                } else if (image) {
                    outputs.images.push_back(pass.write(b.image, usage));
                } else {
                    outputs.buffers.push_back(pass.write(b.buffer, usage));
                }
            }
        }
    return outputs;
}

}  // namespace

ShaderBinding sampled(gpu::ImageHandle image, SampledRead read) {
    return {.kind = Kind::Sampled, .image = image, .read = read};
}
ShaderBinding sampled(gpu::ImageHandle image, VkSampler sampler) {
    return {.kind = Kind::Sampled, .image = image, .sampler = sampler};
}
ShaderBinding sampledStencil(gpu::ImageHandle depthStencil) {
    return {.kind = Kind::SampledStencil, .image = depthStencil};
}
ShaderBinding storageRead(gpu::ImageHandle image) { return {.kind = Kind::StorageRead, .image = image}; }
ShaderBinding storageWrite(gpu::ImageHandle image) { return {.kind = Kind::StorageWrite, .image = image}; }
ShaderBinding storageWriteLevel(gpu::ImageHandle image, uint32_t level) {
    return {.kind = Kind::StorageWrite, .image = image, .level = level};
}
ShaderBinding storageReadWrite(gpu::ImageHandle image) { return {.kind = Kind::StorageReadWrite, .image = image}; }
ShaderBinding bufferRead(gpu::BufferHandle buffer) { return {.kind = Kind::BufferRead, .buffer = buffer}; }
ShaderBinding bufferWrite(gpu::BufferHandle buffer) { return {.kind = Kind::BufferWrite, .buffer = buffer}; }
ShaderBinding bufferReadWrite(gpu::BufferHandle buffer) { return {.kind = Kind::BufferReadWrite, .buffer = buffer}; }
ShaderBinding unbound() { return {}; }

std::vector<gpu::BindingDesc> bindingLayout(const std::vector<ShaderBinding>& bindings) {
    std::vector<gpu::BindingDesc> layout;
    for (uint32_t i = 0; i < bindings.size(); ++i)
        if (bindings[i].kind != Kind::Unbound) layout.push_back({i, descriptorType(bindings[i].kind)});
    return layout;
}

void declareBindings(gpu::FrameGraph::PassBuilder& pass, const std::vector<ShaderBinding>& bindings,
                     ShaderStage stage) {
    declare(pass, {&bindings}, stage);
}

void bindBindings(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, const std::vector<ShaderBinding>& bindings,
                  const gpu::PassResources& res) {
    gpu::Device& device = res.device();
    gpu::DescriptorWriter writer(device, pipeline);
    for (uint32_t i = 0; i < bindings.size(); ++i) {
        const ShaderBinding& b = bindings[i];
        switch (b.kind) {
            case Kind::Unbound: break;
            case Kind::Sampled: {
                VkSampler sampler = b.sampler ? b.sampler
                                    : b.read == SampledRead::Linear ? device.linearClampSampler()
                                                                    : device.nearestClampSampler();
                writer.sampled(i, res.view(b.image), sampler,
                               gpu::isDepthFormat(res.desc(b.image).format)
                                   ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                   : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
                break;
            }
            case Kind::SampledStencil:
                writer.sampled(i, res.stencilView(b.image), device.nearestClampSampler(),
                               VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
                break;
            case Kind::StorageRead:
            case Kind::StorageWrite:
            case Kind::StorageReadWrite:
                writer.storageImage(i, b.level ? res.levelView(b.image, *b.level) : res.storageView(b.image));
                break;
            case Kind::BufferRead:
            case Kind::BufferWrite:
            case Kind::BufferReadWrite: writer.buffer(i, res.buffer(b.buffer)); break;
        }
    }
    writer.bind(cmd);
}

gpu::ImageDesc imageDesc2D(VkFormat format, uint32_t width, uint32_t height) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = width;
    desc.height = height;
    return desc;
}

ComputeOutputs addComputePass(gpu::FrameGraph& graph, ComputePass pass) {
    std::string label = pass.label.empty() ? pass.shader : pass.label;
    std::vector<ComputePass> dispatches;
    dispatches.push_back(std::move(pass));
    return addComputeDispatches(graph, label, std::move(dispatches));
}

ComputeOutputs addComputeDispatches(gpu::FrameGraph& graph, const std::string& label,
                                    std::vector<ComputePass> dispatches) {
    ComputeOutputs outputs;
    const ComputePass& first = dispatches.front();
    gpu::PipelineCache::Request pipelineRequest = gpu::PipelineCache::request<gpu::ComputePipelineDesc>(
        first.shader + gpu::specializationSuffix(first.specialization),
        [desc = gpu::ComputePipelineDesc{first.shader + ".comp", bindingLayout(first.bindings),
                                         uint32_t(first.constants.size()), first.specialization}] { return desc; });
    graph.addPass(
        label, gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& builder) {
            builder.usesPipeline(pipelineRequest);
            std::vector<const std::vector<ShaderBinding>*> lists;
            for (const ComputePass& d : dispatches) lists.push_back(&d.bindings);
            outputs = declare(builder, lists, ShaderStage::Compute);
        },
        [dispatches, pipelineRequest](VkCommandBuffer cmd, const gpu::PassResources& res) {
            const gpu::Pipeline& pipeline = res.pipelines().get(pipelineRequest);
            for (const ComputePass& d : dispatches) {
                bindBindings(cmd, pipeline, d.bindings, res);
                if (!d.constants.empty())
                    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                       uint32_t(d.constants.size()), d.constants.data());
                std::array<uint32_t, 2> texels{};
                if (d.texels) {
                    texels = *d.texels;
                } else {
                    auto written = std::find_if(d.bindings.begin(), d.bindings.end(), [](const ShaderBinding& b) {
                        return b.kind == Kind::StorageWrite ||
                               b.kind == Kind::StorageReadWrite;
                    });
                    if (written == d.bindings.end())
                        throw std::logic_error("compute pass '" + d.shader + "': no image to size the dispatch");
                    const gpu::ImageDesc& size = res.desc(written->image);
                    texels = {size.width, size.height};
                }
                const auto [groupWidth, groupHeight] = d.texelsPerGroup;
                vkCmdDispatch(cmd, (texels[0] + groupWidth - 1) / groupWidth, (texels[1] + groupHeight - 1) / groupHeight,
                              1);
            }
        });
    return outputs;
}

}  // namespace obscura::passes
