#include "passes/tonemap.h"
#include "generated/shader_layouts.h"

namespace obscura::passes {

namespace {
// Mirrors color_lut.cpp's shaper so the shader encodes exactly what the lattice was baked on.
struct TonemapPush {
    float shaperMinStops;
    float shaperRangeStops;
    float middleGrey;
    float lutSize;
    uint32_t alphaIsCoverage;
    float backdropCoverage;
};
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, shaperMinStops);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, shaperRangeStops);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, middleGrey);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, lutSize);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, alphaIsCoverage);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, backdropCoverage);
}  // namespace

gpu::ImageHandle addTonemapPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                gpu::ImageHandle hdrColor, HdrAlpha hdrAlpha, gpu::ImageHandle coverage,
                                gpu::ImageHandle transparentCoverage, const ColorGradingLut& grading) {
    gpu::ImageDesc desc;
    desc.format = kDisplayFormat;
    desc.width = scene.width;
    desc.height = scene.height;
    gpu::ImageHandle display = graph.createImage("display", desc);
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("tonemap", [] {
        return gpu::ComputePipelineDesc{"tonemap.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                         {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},
                                        sizeof(TonemapPush)};
    });
    gpu::Device& device = pipelines.device();
    graph.addPass(
        "tonemap", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(hdrColor, gpu::Usage::SampledCompute);
            pass.read(coverage, gpu::Usage::SampledCompute);
            pass.read(transparentCoverage, gpu::Usage::SampledCompute);
            pass.write(display, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, &scene, &grading, hdrColor, hdrAlpha, coverage, transparentCoverage, display](
            VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::DescriptorWriter(device, pipeline)
                .sampled(0, res.view(hdrColor), device.nearestClampSampler())
                .storageImage(1, res.view(display))
                .sampled(2, res.view(coverage), device.nearestClampSampler())
                .sampled(3, grading.texture()->view, device.linearClampSampler())
                .sampled(4, res.view(transparentCoverage), device.nearestClampSampler())
                .bind(cmd);
            const ColorLut& lut = grading.lut();
            TonemapPush push{lut.shaperMinStops, lut.shaperMaxStops - lut.shaperMinStops, kShaperMiddleGrey,
                             float(lut.size), hdrAlpha == HdrAlpha::Coverage ? 1u : 0u,
                             scene.cameraData.backdropCoverage};
            vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            gpu::dispatch2D(cmd, scene.width, scene.height);
        });
    return display;
}

}  // namespace obscura::passes
