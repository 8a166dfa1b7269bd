#include "passes/ssao.h"

#include "passes/ssao_pattern.h"

namespace obscura::passes {
namespace {

// rgb: the G-buffer's best-fit normal of the pixel whose depth a half-resolution texel took; a:
// which pixel of the 2x2 that was (shaders/ssao_downsample.comp).
constexpr VkFormat kSsaoNormalFormat = kNormalRoughnessFormat;

// Mirrors the push constants of shaders/ssao_obscurance.comp.
struct ObscurancePush {
    std::array<uint32_t, kSsaoPatternSide * kSsaoPatternSide> pattern;
    float radius;
    float intensity;
};

// Mirrors the push constants of shaders/ssao_blur.comp: the texel step between taps.
struct BlurPush {
    int32_t axis[2];
};

gpu::ImageDesc halfResolution(const FrameScene& scene, VkFormat format) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = (scene.width + 1) / 2;
    desc.height = (scene.height + 1) / 2;
    return desc;
}

struct HalfResolutionGeometry {
    gpu::ImageHandle depth;
    gpu::ImageHandle normal;
};

// Full-resolution depth and normals to one texel per 2x2 pixels (shaders/ssao_downsample.comp).
HalfResolutionGeometry addDownsamplePass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                         const GBuffer& gb) {
    HalfResolutionGeometry half{graph.createImage("ssaoHalfDepth", halfResolution(scene, kSsaoDepthFormat)),
                                graph.createImage("ssaoHalfNormal", halfResolution(scene, kSsaoNormalFormat))};
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("ssao_downsample", [] {
        return gpu::ComputePipelineDesc{"ssao_downsample.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                         {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                         {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        0};
    });
    gpu::Device& device = pipelines.device();
    graph.addPass(
        "ssao_downsample", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(gb.depth, gpu::Usage::SampledCompute);
            pass.read(gb.normalRoughness, gpu::Usage::SampledCompute);
            pass.write(half.depth, gpu::Usage::StorageImageWrite);
            pass.write(half.normal, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, &scene, gb, half](VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            gpu::DescriptorWriter(device, pipeline)
                .buffer(0, scene.camera->buffer)
                .sampled(1, res.view(gb.depth), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                .sampled(2, res.view(gb.normalRoughness), nearest)
                .storageImage(3, res.view(half.depth))
                .storageImage(4, res.view(half.normal))
                .bind(cmd);
            const gpu::ImageDesc& size = res.desc(half.depth);
            gpu::dispatch2D(cmd, size.width, size.height);
        });
    return half;
}

// Volumetric obscurance with 4 samples per half-resolution pixel (shaders/ssao_obscurance.comp).
gpu::ImageHandle addObscurancePass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                   const HalfResolutionGeometry& half, const SsaoSettings& settings) {
    gpu::ImageHandle accessibility =
        graph.createImage("ssaoNoisy", halfResolution(scene, kSsaoAccessibilityFormat));
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("ssao_obscurance", [] {
        return gpu::ComputePipelineDesc{"ssao_obscurance.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                         {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        sizeof(ObscurancePush)};
    });
    static const auto kPattern = packSsaoSamplePattern(ssaoSamplePattern());
    ObscurancePush push{kPattern, settings.radius, settings.intensity};
    gpu::Device& device = pipelines.device();
    graph.addPass(
        "ssao_obscurance", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(half.depth, gpu::Usage::SampledCompute);
            pass.read(half.normal, gpu::Usage::SampledCompute);
            pass.write(accessibility, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, &scene, half, accessibility, push](VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            gpu::DescriptorWriter(device, pipeline)
                .buffer(0, scene.camera->buffer)
                .sampled(1, res.view(half.depth), nearest)
                .sampled(2, res.view(half.normal), nearest)
                .storageImage(3, res.view(accessibility))
                .bind(cmd);
            vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            const gpu::ImageDesc& size = res.desc(accessibility);
            gpu::dispatch2D(cmd, size.width, size.height);
        });
    return accessibility;
}

// One axis of the separable bilateral blur (shaders/ssao_blur.comp).
gpu::ImageHandle addBlurPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                             const std::string& name, gpu::ImageHandle input, gpu::ImageHandle halfDepth,
                             BlurPush push) {
    gpu::ImageHandle output = graph.createImage(name, halfResolution(scene, kSsaoAccessibilityFormat));
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("ssao_blur", [] {
        return gpu::ComputePipelineDesc{"ssao_blur.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        sizeof(BlurPush)};
    });
    gpu::Device& device = pipelines.device();
    graph.addPass(
        name, gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(input, gpu::Usage::SampledCompute);
            pass.read(halfDepth, gpu::Usage::SampledCompute);
            pass.write(output, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, input, halfDepth, output, push](VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            gpu::DescriptorWriter(device, pipeline)
                .sampled(0, res.view(input), nearest)
                .sampled(1, res.view(halfDepth), nearest)
                .storageImage(2, res.view(output))
                .bind(cmd);
            vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            const gpu::ImageDesc& size = res.desc(output);
            gpu::dispatch2D(cmd, size.width, size.height);
        });
    return output;
}

}  // namespace

SsaoResult addSsaoPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                         const GBuffer& gbuffer, const SsaoSettings& settings) {
    HalfResolutionGeometry half = addDownsamplePass(graph, pipelines, scene, gbuffer);
    gpu::ImageHandle noisy = addObscurancePass(graph, pipelines, scene, half, settings);
    // XXX: seed 004's temporal accumulation with reprojection is not done yet; it belongs here,
    // between the obscurance and the blur, taking the previous frame's result as a history input.
    gpu::ImageHandle horizontal =
        addBlurPass(graph, pipelines, scene, "ssao_blur_horizontal", noisy, half.depth, {{1, 0}});
    gpu::ImageHandle accessibility =
        addBlurPass(graph, pipelines, scene, "ssao_blur_vertical", horizontal, half.depth, {{0, 1}});
    return {accessibility, half.depth};
}

}  // namespace obscura::passes
