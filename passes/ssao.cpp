#include "passes/ssao.h"

#include "generated/shader_layouts.h"
#include "pass_support/ssao_pattern.h"

#include <cmath>

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
    std::array<float, 2> frameRotation;
};
OBSCURA_SHADER_OFFSET(ObscurancePush, ssao_obscurance_comp::Push, pattern);
OBSCURA_SHADER_OFFSET(ObscurancePush, ssao_obscurance_comp::Push, radius);
OBSCURA_SHADER_OFFSET(ObscurancePush, ssao_obscurance_comp::Push, intensity);
OBSCURA_SHADER_OFFSET(ObscurancePush, ssao_obscurance_comp::Push, frameRotation);

// Mirrors the push constants of shaders/ssao_temporal.comp.
struct TemporalPush {
    Mat4 viewToPreviousView;
    float maxFrames;
    uint32_t historyValid;
};
OBSCURA_SHADER_OFFSET(TemporalPush, ssao_temporal_comp::Push, viewToPreviousView);
OBSCURA_SHADER_OFFSET(TemporalPush, ssao_temporal_comp::Push, maxFrames);
OBSCURA_SHADER_OFFSET(TemporalPush, ssao_temporal_comp::Push, historyValid);

// Mirrors the push constants of shaders/ssao_blur.comp: the texel step between taps.
struct BlurPush {
    int32_t axis[2];
};
OBSCURA_SHADER_OFFSET(BlurPush, ssao_blur_comp::Push, axis);

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
                                        {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
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
                                   const HalfResolutionGeometry& half, const SsaoSettings& settings,
                                   uint64_t frame) {
    gpu::ImageHandle accessibility =
        graph.createImage("ssaoNoisy", halfResolution(scene, kSsaoAccessibilityFormat));
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("ssao_obscurance", [] {
        return gpu::ComputePipelineDesc{"ssao_obscurance.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                         {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        sizeof(ObscurancePush)};
    });
    static const auto kPattern = packSsaoSamplePattern(ssaoSamplePattern());
    // The golden angle turns each frame's pattern away from all earlier ones.
    const double turn = 2.39996322972865332 * double(frame % 1024);
    ObscurancePush push{kPattern, settings.radius, settings.intensity,
                        {float(std::cos(turn)), float(std::sin(turn))}};
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

// Temporal accumulation with reprojection (shaders/ssao_temporal.comp): writes this frame's history
// images from the noisy obscurance and last frame's; returns the accumulated accessibility.
gpu::ImageHandle addTemporalPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                 const HalfResolutionGeometry& half, gpu::ImageHandle noisy, SsaoHistory& history) {
    gpu::Device& device = pipelines.device();
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    gpu::ImageDesc accessibilityDesc = halfResolution(scene, kSsaoHistoryFormat);
    gpu::ImageDesc depthDesc = halfResolution(scene, kSsaoDepthFormat);
    accessibilityDesc.usage = depthDesc.usage = usage;
    bool created = history.accessibility.ensure(device, accessibilityDesc, "ssaoHistory");
    created = history.depth.ensure(device, depthDesc, "ssaoHistoryDepth") || created;
    if (created) history.valid = false;
    gpu::HistoryImages::Imported accessibility = history.accessibility.import(graph, "ssaoHistory");
    gpu::HistoryImages::Imported depth = history.depth.import(graph, "ssaoHistoryDepth");
    TemporalPush push{history.viewToPreviousView, float(kSsaoHistoryFrames),
                      history.valid && accessibility.previousWritten ? 1u : 0u};
    gpu::ImageHandle previous = accessibility.previous, previousDepth = depth.previous;
    ++history.frame;

    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("ssao_temporal", [] {
        return gpu::ComputePipelineDesc{"ssao_temporal.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                         {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                         {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        sizeof(TemporalPush)};
    });
    gpu::ImageHandle out = accessibility.current, outDepth = depth.current;
    graph.addPass(
        "ssao_temporal", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(noisy, gpu::Usage::SampledCompute);
            pass.read(half.depth, gpu::Usage::SampledCompute);
            pass.read(half.normal, gpu::Usage::SampledCompute);
            pass.read(previous, gpu::Usage::SampledCompute);
            pass.read(previousDepth, gpu::Usage::SampledCompute);
            pass.write(out, gpu::Usage::StorageImageWrite);
            pass.write(outDepth, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, &scene, half, noisy, previous, previousDepth, out, outDepth,
         push](VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            gpu::DescriptorWriter(device, pipeline)
                .buffer(0, scene.camera->buffer)
                .sampled(1, res.view(noisy), nearest)
                .sampled(2, res.view(half.depth), nearest)
                .sampled(3, res.view(half.normal), nearest)
                .sampled(4, res.view(previous), nearest)
                .sampled(5, res.view(previousDepth), nearest)
                .storageImage(6, res.view(out))
                .storageImage(7, res.view(outDepth))
                .bind(cmd);
            vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            const gpu::ImageDesc& size = res.desc(out);
            gpu::dispatch2D(cmd, size.width, size.height);
        });
    return out;
}

}  // namespace

SsaoResult addSsaoPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                         const GBuffer& gbuffer, const SsaoSettings& settings, SsaoHistory& history) {
    HalfResolutionGeometry half = addDownsamplePass(graph, pipelines, scene, gbuffer);
    gpu::ImageHandle noisy = addObscurancePass(graph, pipelines, scene, half, settings, history.frame);
    SsaoResult result;
    gpu::ImageHandle accumulated = addTemporalPass(graph, pipelines, scene, half, noisy, history);
    gpu::ImageHandle horizontal =
        addBlurPass(graph, pipelines, scene, "ssao_blur_horizontal", accumulated, half.depth, {{1, 0}});
    result.accessibility =
        addBlurPass(graph, pipelines, scene, "ssao_blur_vertical", horizontal, half.depth, {{0, 1}});
    result.halfDepth = half.depth;
    return result;
}

void keepSsaoHistory(const gpu::FrameGraph& graph, SsaoHistory& history) {
    history.accessibility.keep(graph);
    history.depth.keep(graph);
}

}  // namespace obscura::passes
