#include "passes/image_compute_pass.h"

namespace obscura::passes {

gpu::ImageDesc chainImage(VkFormat format, uint32_t width, uint32_t height) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = width;
    desc.height = height;
    return desc;
}

void addImageComputePass(gpu::FrameGraph& graph, PipelineCache& pipelines, ImageComputePass desc) {
    const bool withCamera = desc.camera != VK_NULL_HANDLE;
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>(desc.shader, [&] {
        gpu::ComputePipelineDesc d{desc.shader + ".comp", {}, uint32_t(desc.constants.size())};
        uint32_t binding = 0;
        for (size_t i = 0; i < desc.inputs.size(); ++i)
            d.bindings.push_back({binding++, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
        for (size_t i = 0; i < desc.outputs.size(); ++i) d.bindings.push_back({binding++, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
        if (withCamera) d.bindings.push_back({binding++, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        for (size_t i = 0; i < desc.storageBuffers.size(); ++i)
            d.bindings.push_back({binding++, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        return d;
    });
    gpu::Device& device = pipelines.device();
    std::string label = desc.label.empty() ? desc.shader : desc.label;
    graph.addPass(
        label, gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            for (const SampledInput& input : desc.inputs) pass.read(input.image, gpu::Usage::SampledCompute);
            for (gpu::ImageHandle output : desc.outputs) pass.write(output, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, desc](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::DescriptorWriter writer(device, pipeline);
            uint32_t binding = 0;
            for (const SampledInput& input : desc.inputs) {
                VkSampler sampler =
                    input.read == SampledRead::Linear ? device.linearClampSampler() : device.nearestClampSampler();
                writer.sampled(binding++, res.view(input.image), sampler,
                               input.read == SampledRead::Depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                                                : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
            }
            for (gpu::ImageHandle output : desc.outputs) writer.storageImage(binding++, res.view(output));
            if (desc.camera != VK_NULL_HANDLE) writer.buffer(binding++, desc.camera);
            for (VkBuffer buffer : desc.storageBuffers) writer.buffer(binding++, buffer);
            writer.bind(cmd);
            if (!desc.constants.empty())
                vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                   uint32_t(desc.constants.size()), desc.constants.data());
            const gpu::ImageDesc& size = res.desc(desc.outputs.front());
            gpu::dispatch2D(cmd, size.width, size.height, desc.texelsPerGroup);
        });
}

}  // namespace obscura::passes
