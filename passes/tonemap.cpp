#include "passes/tonemap.h"

namespace obscura::passes {

gpu::ImageHandle addTonemapPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                gpu::ImageHandle hdrColor, gpu::ImageHandle coverage) {
    gpu::ImageDesc desc;
    desc.format = kDisplayFormat;
    desc.width = scene.width;
    desc.height = scene.height;
    gpu::ImageHandle display = graph.createImage("display", desc);
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("tonemap", [] {
        return gpu::ComputePipelineDesc{"tonemap.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                         {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},
                                        0};
    });
    gpu::Device& device = pipelines.device();
    graph.addPass(
        "tonemap", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(hdrColor, gpu::Usage::StorageImageRead);
            pass.read(coverage, gpu::Usage::SampledCompute);
            pass.write(display, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, &scene, hdrColor, coverage, display](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::DescriptorWriter(device, pipeline)
                .storageImage(0, res.view(hdrColor))
                .storageImage(1, res.view(display))
                .sampled(2, res.view(coverage), device.nearestClampSampler())
                .bind(cmd);
            gpu::dispatch2D(cmd, scene.width, scene.height);
        });
    return display;
}

}  // namespace obscura::passes
