#include "passes/temporal_aa.h"

#include "generated/shader_layouts.h"
#include "passes/image_compute_pass.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace obscura::passes {
namespace {

// The 2TX weight's K (seed 000: w = 0.5 max(0, 1 - K sqrt(| |v_c| - |v_p| |))) for velocities in
// pixels: a change of one pixel in the velocity's length drops the last frame entirely. (SMAA's
// own scale, 30 for velocities in texture coordinates, does nearly the same at 1080p: 0.91.)
constexpr float kSmaa2txVelocityWeight = 1.0f;

// Mirrors TemporalAaConstants in shaders/common/temporal_aa_common.glsl (std140).
struct TemporalAaConstants {
    Mat4 currentClipToPreviousClip;
    Mat4 currentClipToPreviousView;
    Mat4 worldToPreviousClip;
    Mat4 worldToPreviousView;
    std::array<float, 4> weights;    // x K_lowfreq, y K_hifreq, z 2TX's velocity weight
    std::array<uint32_t, 4> frames;  // x history valid, y held frames, z frames to converge, w TemporalAaFlags
};
OBSCURA_SHADER_OFFSET(TemporalAaConstants, TemporalAaConstants, currentClipToPreviousClip);
OBSCURA_SHADER_OFFSET(TemporalAaConstants, TemporalAaConstants, currentClipToPreviousView);
OBSCURA_SHADER_OFFSET(TemporalAaConstants, TemporalAaConstants, worldToPreviousClip);
OBSCURA_SHADER_OFFSET(TemporalAaConstants, TemporalAaConstants, worldToPreviousView);
OBSCURA_SHADER_OFFSET(TemporalAaConstants, TemporalAaConstants, weights);
OBSCURA_SHADER_OFFSET(TemporalAaConstants, TemporalAaConstants, frames);
// Mirrors TAA_FLAG_* in shaders/common/temporal_aa_common.glsl.
enum TemporalAaFlags : uint32_t { kTemporalAaEdgeAa = 1u, kTemporalAaColorHasCoverage = 2u };
static_assert(sizeof(TemporalAaConstants) == 4 * 64 + 32);

// Van der Corput: the digits of `index` in `base`, mirrored about the radix point.
double radicalInverse(uint32_t index, uint32_t base) {
    double inverse = 0.0, digitWeight = 1.0 / base;
    for (; index > 0; index /= base, digitWeight /= base) inverse += digitWeight * (index % base);
    return inverse;
}

// [0, 1) rotated by half and centred: 0 -> 0, values stay in [-0.5, 0.5).
double centredRotation(double unit) { return unit + 0.5 - std::floor(unit + 0.5) - 0.5; }

}  // namespace

VkFormat temporalAaDepthFormat(TemporalAaMode mode) {
    return mode == TemporalAaMode::Smaa2tx ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R32_SFLOAT;
}

std::array<double, 2> temporalAaJitter(TemporalAaMode mode, uint32_t index, uint32_t count) {
    if (mode == TemporalAaMode::Smaa2tx)
        return index % kSmaa2txFrames == 0 ? std::array{0.25, 0.25} : std::array{-0.25, -0.25};
    uint32_t i = count > 0 ? index % count : 0;
    return {centredRotation(radicalInverse(i, 2)), centredRotation(radicalInverse(i, 3))};
}

gpu::ImageHandle addTemporalAaPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                   const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                   gpu::ImageHandle transparentCoverage, const TemporalAaSettings& settings,
                                   const TemporalAaFrame& frame, TemporalAaHistory& history) {
    gpu::Device& device = pipelines.device();
    gpu::ImageDesc colorDesc;
    colorDesc.format = kTemporalAaColorFormat;
    colorDesc.width = scene.width;
    colorDesc.height = scene.height;
    colorDesc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    gpu::ImageDesc depthDesc = colorDesc;
    depthDesc.format = temporalAaDepthFormat(settings.mode);
    // New images (first use, resize) hold nothing: previousWritten says so.
    history.color.ensure(device, colorDesc, "temporalAaHistory");
    history.depth.ensure(device, depthDesc, "temporalAaHistoryDepth");
    gpu::HistoryImages::Imported color = history.color.import(graph, "temporalAaHistory");
    gpu::HistoryImages::Imported depth = history.depth.import(graph, "temporalAaHistoryDepth");

    TemporalAaConstants constants{frame.currentClipToPreviousClip,
                                  frame.currentClipToPreviousView,
                                  frame.worldToPreviousClip,
                                  frame.worldToPreviousView,
                                  {settings.kLowFreq, settings.kHighFreq, kSmaa2txVelocityWeight, 0.0f},
                                  {frame.historyValid && color.previousWritten ? 1u : 0u,
                                   frame.heldFrames, frame.framesToConverge,
                                   (frame.edgeAa ? kTemporalAaEdgeAa : 0u) |
                                       (frame.colorHasCoverage ? kTemporalAaColorHasCoverage : 0u)}};
    gpu::BufferPtr constantBuffer = device.createFrameBuffer(sizeof(constants), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                             "temporalAaConstants");
    std::memcpy(constantBuffer->mapped(), &constants, sizeof(constants));

    // 1TX's result is its accumulation; 2TX keeps the raw frame as history and resolves apart. An
    // unchanged scene runs the still's plain running mean, its own shader: lavapipe pays for both
    // sides of a branch, even a uniform one.
    const bool twoFrame = settings.mode == TemporalAaMode::Smaa2tx;
    const bool still = !twoFrame && constants.frames[0] != 0 && frame.unchanged;
    const char* variant = twoFrame ? "temporal_aa_2tx" : still ? "temporal_aa_still" : "temporal_aa";
    gpu::ImageHandle resolved = color.current;
    if (twoFrame) {
        gpu::ImageDesc resolvedDesc = colorDesc;
        resolvedDesc.usage = 0;
        resolved = graph.createImage("temporalAaResolved", resolvedDesc);
    }
    std::vector<gpu::BindingDesc> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                              {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                              {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                              {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                              {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                              {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                              {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                              {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                              {9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                              {10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                              {11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                              {12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    if (twoFrame) bindings.push_back({8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>(
        variant, [&] { return gpu::ComputePipelineDesc{std::string(variant) + ".comp", bindings, 0}; });
    graph.addPass(
        variant, gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(hdrColor, gpu::Usage::SampledCompute);
            pass.read(gbuffer.depth, gpu::Usage::SampledCompute);
            pass.read(transparentCoverage, gpu::Usage::SampledCompute);
            pass.read(gbuffer.instance, gpu::Usage::SampledCompute);
            pass.read(color.previous, gpu::Usage::SampledCompute);
            pass.read(depth.previous, gpu::Usage::SampledCompute);
            pass.write(color.current, gpu::Usage::StorageImageWrite);
            pass.write(depth.current, gpu::Usage::StorageImageWrite);
            if (twoFrame) pass.write(resolved, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, &scene, gbuffer, hdrColor, transparentCoverage, color, depth, resolved, twoFrame,
         constantBuffer](VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            gpu::DescriptorWriter writer(device, pipeline);
            writer.buffer(0, scene.camera->buffer)
                .buffer(1, constantBuffer->buffer)
                .sampled(2, res.view(hdrColor), nearest)
                .sampled(3, res.view(gbuffer.depth), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                .sampled(4, res.view(color.previous), nearest)
                .sampled(5, res.view(depth.previous), nearest)
                .storageImage(6, res.view(color.current))
                .storageImage(7, res.view(depth.current))
                .sampled(9, res.view(transparentCoverage), nearest)
                .sampled(10, res.view(gbuffer.instance), nearest)
                .buffer(11, scene.instances->buffer)
                .buffer(12, scene.instanceReprojections->buffer);
            if (twoFrame) writer.storageImage(8, res.view(resolved));
            writer.bind(cmd);
            gpu::dispatch2D(cmd, scene.width, scene.height);
        });
    return resolved;
}

gpu::ImageHandle addTemporalAaSamplePass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                         const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                         gpu::ImageHandle transparentCoverage) {
    gpu::ImageHandle sample =
        graph.createImage("temporalAaSample", chainImage(kTemporalAaColorFormat, scene.width, scene.height));
    ImageComputePass pass{"temporal_aa_sample",
                          {{hdrColor, SampledRead::Nearest},
                           {gbuffer.depth, SampledRead::Depth},
                           {transparentCoverage, SampledRead::Nearest}},
                          {sample},
                          {}};
    pass.camera = scene.camera->buffer;
    addImageComputePass(graph, pipelines, pass);
    return sample;
}

void keepTemporalAaHistory(const gpu::FrameGraph& graph, TemporalAaHistory& history) {
    history.color.keep(graph);
    history.depth.keep(graph);
}

}  // namespace obscura::passes
