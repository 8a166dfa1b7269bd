#include "passes/ssao.h"

#include "generated/shader_layouts.h"
#include "pass_support/ssao_pattern.h"
#include "passes/shader_pass.h"

#include <cmath>

namespace obscura::passes {
namespace {

// rgb: the G-buffer's best-fit normal of the pixel whose depth a half-resolution texel took; a:
// which pixel of the 2x2 that was (heldPixel, shaders/common/ssao_common.glsl).
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

// Mirrors the push constants of shaders/ssao_temporal_blur.comp.
struct TemporalPush {
    Mat4 viewToPreviousView;
    float maxFrames;
    uint32_t historyValid;
};
OBSCURA_SHADER_OFFSET(TemporalPush, ssao_temporal_blur_comp::Push, viewToPreviousView);
OBSCURA_SHADER_OFFSET(TemporalPush, ssao_temporal_blur_comp::Push, maxFrames);
OBSCURA_SHADER_OFFSET(TemporalPush, ssao_temporal_blur_comp::Push, historyValid);

gpu::ImageDesc halfResolution(const FrameScene& scene, VkFormat format) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = (scene.width + 1) / 2;
    desc.height = (scene.height + 1) / 2;
    return desc;
}

// Volumetric obscurance with 4 samples per half-resolution pixel, which also takes the
// half-resolution geometry from the G-buffer (shaders/ssao_obscurance.comp).
struct Obscurance {
    gpu::ImageHandle halfDepth;
    gpu::ImageHandle halfNormal;
    gpu::ImageHandle noisy;
};
Obscurance addObscurancePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gb,
                             const SsaoSettings& settings, uint64_t frame) {
    static const auto kPattern = packSsaoSamplePattern(ssaoSamplePattern());
    // The golden angle turns each frame's pattern away from all earlier ones.
    const double turn = 2.39996322972865332 * double(frame % 1024);
    ObscurancePush push{kPattern, settings.radius, settings.intensity,
                        {float(std::cos(turn)), float(std::sin(turn))}};
    std::vector<gpu::ImageHandle> written =
        addComputePass(graph,
                       {"ssao_obscurance",
                        {bufferRead(scene.buffers.camera), sampled(gb.depth), sampled(gb.normalRoughness),
                         storageWrite(graph.createImage("ssaoHalfDepth", halfResolution(scene, kSsaoDepthFormat))),
                         storageWrite(graph.createImage("ssaoHalfNormal", halfResolution(scene, kSsaoNormalFormat))),
                         storageWrite(graph.createImage("ssaoNoisy", halfResolution(scene, kSsaoAccessibilityFormat)))},
                        bytesOf(push)})
            .images;
    return {written[0], written[1], written[2]};
}

// Temporal accumulation with reprojection, then the bilateral blur, in one pass
// (shaders/ssao_temporal_blur.comp): writes this frame's history images from the noisy obscurance
// and last frame's; returns the blurred accessibility.
gpu::ImageHandle addTemporalBlurPass(gpu::FrameGraph& graph, const FrameScene& scene, const Obscurance& obscurance,
                                     SsaoHistory& history) {
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    gpu::ImageDesc accessibilityDesc = halfResolution(scene, kSsaoHistoryFormat);
    gpu::ImageDesc depthDesc = halfResolution(scene, kSsaoDepthFormat);
    accessibilityDesc.usage = depthDesc.usage = usage;
    gpu::FrameGraph::History accessibility = graph.addHistory("ssaoHistory", history.accessibility, accessibilityDesc);
    gpu::FrameGraph::History depth = graph.addHistory("ssaoHistoryDepth", history.depth, depthDesc);
    // New images (the first frame, another size) hold nothing to reproject.
    const bool valid = history.valid && !accessibility.previousEmpty && !depth.previousEmpty;
    TemporalPush push{history.viewToPreviousView, float(kSsaoHistoryFrames), valid ? 1u : 0u};
    ++history.frame;
    ComputePass pass{"ssao_temporal_blur",
                     {bufferRead(scene.buffers.camera), sampled(obscurance.noisy), sampled(obscurance.halfDepth),
                      sampled(obscurance.halfNormal), sampled(accessibility.previous), sampled(depth.previous),
                      storageWrite(accessibility.current), storageWrite(depth.current),
                      storageWrite(graph.createImage("ssaoBlurred", halfResolution(scene, kSsaoAccessibilityFormat)))},
                     bytesOf(push)};
    pass.texelsPerGroup = {16, 32};  // ssao_temporal_blur.comp's tile
    return addComputePass(graph, std::move(pass)).images[2];
}

}  // namespace

SsaoResult addSsaoPasses(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gbuffer,
                         const SsaoSettings& settings, SsaoHistory& history) {
    Obscurance obscurance = addObscurancePass(graph, scene, gbuffer, settings, history.frame);
    return {addTemporalBlurPass(graph, scene, obscurance, history), obscurance.halfDepth};
}

}  // namespace obscura::passes
