#include "passes/accumulate.h"
#include "generated/shader_layouts.h"

namespace obscura::passes {
namespace {

// Mirrors the push constants of shaders/accumulate.comp.
struct AccumulatePush {
    float weight;
    uint32_t first;
};
OBSCURA_SHADER_OFFSET(AccumulatePush, accumulate_comp::Push, weight);
OBSCURA_SHADER_OFFSET(AccumulatePush, accumulate_comp::Push, first);

}  // namespace

void addAccumulatePass(gpu::FrameGraph& graph, PipelineCache& pipelines, gpu::ImageHandle hdrColor,
                       gpu::ImageHandle accumulation, float weight, bool first) {
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("accumulate", [] {
        return gpu::ComputePipelineDesc{"accumulate.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        sizeof(AccumulatePush)};
    });
    gpu::Device& device = pipelines.device();
    AccumulatePush push{weight, first ? 1u : 0u};
    graph.addPass(
        "accumulate", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(hdrColor, gpu::Usage::SampledCompute);
            if (!first) pass.read(accumulation, gpu::Usage::StorageImageRead);
            pass.write(accumulation, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, hdrColor, accumulation, push](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::DescriptorWriter(device, pipeline)
                .sampled(0, res.view(hdrColor), device.nearestClampSampler())
                .storageImage(1, res.view(accumulation))
                .bind(cmd);
            vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            const gpu::ImageDesc& size = res.desc(accumulation);
            gpu::dispatch2D(cmd, size.width, size.height);
        });
    graph.markOutput(accumulation);
}

gpu::ImageHandle addAccumulationResolvePass(gpu::FrameGraph& graph, PipelineCache& pipelines,
                                            gpu::ImageHandle accumulation, VkFormat format) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = graph.imageDesc(accumulation).width;
    desc.height = graph.imageDesc(accumulation).height;
    gpu::ImageHandle resolved = graph.createImage("accumulationResolved", desc);
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("accumulate_resolve", [] {
        return gpu::ComputePipelineDesc{"accumulate_resolve.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        0};
    });
    gpu::Device& device = pipelines.device();
    graph.addPass(
        "accumulate_resolve", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(accumulation, gpu::Usage::StorageImageRead);
            pass.write(resolved, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, accumulation, resolved](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::DescriptorWriter(device, pipeline)
                .storageImage(0, res.view(accumulation))
                .storageImage(1, res.view(resolved))
                .bind(cmd);
            const gpu::ImageDesc& size = res.desc(resolved);
            gpu::dispatch2D(cmd, size.width, size.height);
        });
    return resolved;
}

}  // namespace obscura::passes
