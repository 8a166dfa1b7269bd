#include "passes/lighting.h"

#include <optional>

namespace obscura::passes {
namespace {

constexpr uint32_t kLightingTileSize = 16;  // lighting.comp's TILE_SIZE: one workgroup culls lights per tile

std::vector<gpu::BindingDesc> pixelFrequencyBindings() {
    return {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
            {9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {13, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
            {14, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {15, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {16, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}};
}

gpu::ComputePipelineDesc describeLightingPipeline() {
    return {"lighting.comp", pixelFrequencyBindings(), 0};
}

// The PER_SAMPLE_LIGHTING build of lighting.comp: the multisampled G-buffer and the tagged count.
gpu::ComputePipelineDesc describePerSampleLightingPipeline() {
    std::vector<gpu::BindingDesc> bindings = pixelFrequencyBindings();
    for (uint32_t b = 17; b <= 20; ++b) bindings.push_back({b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
    bindings.push_back({21, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    return {"lighting_per_sample.comp", bindings, 0};
}

}  // namespace

gpu::ImageHandle addLightingPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                 const GBuffer& gb, const SsaoResult& ambient, gpu::ImageHandle shadowAtlas,
                                 const EnvironmentLighting& environment,
                                 LightAccumulation format, const PerSampleLighting* perSample) {
    gpu::ImageDesc desc;
    desc.format = format == LightAccumulation::HalfFloat ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                         : VK_FORMAT_B10G11R11_UFLOAT_PACK32;
    desc.width = scene.width;
    desc.height = scene.height;
    gpu::ImageHandle accumulation = graph.createImage("lightAccumulation", desc);
    const gpu::Pipeline& pipeline =
        perSample ? pipelines.get<gpu::ComputePipelineDesc>("lighting_per_sample", describePerSampleLightingPipeline)
                  : pipelines.get<gpu::ComputePipelineDesc>("lighting", describeLightingPipeline);
    std::optional<PerSampleLighting> samples;
    if (perSample) samples = *perSample;
    gpu::Device& device = pipelines.device();

    graph.addPass(
        "lighting", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(gb.depth, gpu::Usage::SampledCompute);
            pass.read(gb.normalRoughness, gpu::Usage::SampledCompute);
            pass.read(gb.albedoMetallic, gpu::Usage::SampledCompute);
            pass.read(gb.instance, gpu::Usage::SampledCompute);
            pass.read(ambient.accessibility, gpu::Usage::SampledCompute);
            pass.read(ambient.halfDepth, gpu::Usage::SampledCompute);
            pass.read(shadowAtlas, gpu::Usage::SampledCompute);
            pass.read(environment.prefiltered, gpu::Usage::SampledCompute);
            pass.read(environment.irradiance, gpu::Usage::StorageBufferRead);
            pass.write(accumulation, gpu::Usage::StorageImageWrite);
            if (samples) {
                pass.read(samples->multisampled.depth, gpu::Usage::SampledCompute);
                pass.read(samples->multisampled.normalRoughness, gpu::Usage::SampledCompute);
                pass.read(samples->multisampled.albedoMetallic, gpu::Usage::SampledCompute);
                pass.read(samples->multisampled.instance, gpu::Usage::SampledCompute);
                pass.write(samples->taggedPixelCount, gpu::Usage::StorageBufferWrite);
            }
        },
        [&device, &pipeline, &scene, gb, ambient, shadowAtlas, environment, accumulation, samples](
            VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            gpu::DescriptorWriter writer(device, pipeline);
            if (samples)
                writer
                    .sampled(17, res.view(samples->multisampled.depth), nearest,
                             VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                    .sampled(18, res.view(samples->multisampled.normalRoughness), nearest)
                    .sampled(19, res.view(samples->multisampled.albedoMetallic), nearest)
                    .sampled(20, res.view(samples->multisampled.instance), nearest)
                    .buffer(21, res.buffer(samples->taggedPixelCount));
            writer
                .buffer(0, scene.camera->buffer)
                .buffer(1, scene.instances->buffer)
                .buffer(2, scene.materials->buffer)
                .buffer(3, scene.lights->buffer)
                .sampled(4, res.view(gb.depth), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                .sampled(5, res.view(gb.normalRoughness), nearest)
                .sampled(6, res.view(gb.albedoMetallic), nearest)
                .sampled(7, res.view(gb.instance), nearest)
                .storageImage(8, res.view(accumulation))
                .sampled(9, res.view(ambient.accessibility), nearest)
                .sampled(10, res.view(ambient.halfDepth), nearest)
                .buffer(11, scene.shadows.records->buffer)
                .sampled(12, res.view(shadowAtlas), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                .sampled(13, res.stencilView(gb.depth), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                .buffer(14, scene.environment->buffer)
                .buffer(15, res.buffer(environment.irradiance))
                .sampled(16, res.view(environment.prefiltered), environment.sampler)
                .bind(cmd);
            gpu::dispatch2D(cmd, scene.width, scene.height, kLightingTileSize);
        });
    return accumulation;
}

}  // namespace obscura::passes
