#include "passes/temporal_aa.h"

#include "generated/shader_layouts.h"
#include "passes/shader_pass.h"

#include <cmath>
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

// The second dimension of Sobol's sequence (its generator matrix is Pascal's triangle mod 2): with
// the base-2 radical inverse, the first 2^m points put one in each of the 2^m rows and columns and in
// every other elementary box of area 2^-m (a (0, 2)-sequence).
double sobolSecond(uint32_t index) {
    uint32_t bits = 0;
    for (uint32_t direction = 1u << 31; index > 0; index >>= 1, direction ^= direction >> 1)
        if (index & 1u) bits ^= direction;
    return bits / 4294967296.0;
}

// [0, 1) turned by half and centred: 0 -> 0, values stay in [-0.5, 0.5).
double centredRotation(double unit) { return unit + 0.5 - std::floor(unit + 0.5) - 0.5; }

}  // namespace

VkFormat temporalAaDepthFormat(TemporalAaMode mode) {
    return mode == TemporalAaMode::Smaa2tx ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R32_SFLOAT;
}

std::array<double, 2> temporalAaJitter(TemporalAaMode mode, uint32_t index, uint32_t count) {
    if (mode == TemporalAaMode::Smaa2tx)
        return index % kSmaa2txFrames == 0 ? std::array{0.25, 0.25} : std::array{-0.25, -0.25};
    const uint32_t i = count > 0 ? index % count : 0;
    // Both coordinates turned by half a pixel about the pixel centre; y then moved from its
    // strata's lower edges (multiples of 1 / count from -0.5) to their centres, but for frame 0,
    // which stays at the pixel centre, the lower edge of its stratum.
    const double toCentre = i > 0 ? 0.5 / count : 0.0;
    return {centredRotation(radicalInverse(i, 2)), centredRotation(sobolSecond(i)) + toCentre};
}

gpu::ImageHandle addTemporalAaPass(gpu::FrameGraph& graph, const FrameScene& scene,
                                   const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                   gpu::ImageHandle transparentCoverage, const TemporalAaSettings& settings,
                                   const TemporalAaFrame& frame, TemporalAaHistory& history) {
    gpu::ImageDesc colorDesc;
    colorDesc.format = temporalAaHistoryFormat(frame.framesToConverge);
    colorDesc.width = scene.width;
    colorDesc.height = scene.height;
    colorDesc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    gpu::ImageDesc depthDesc = colorDesc;
    depthDesc.format = temporalAaDepthFormat(settings.mode);
    // New images (the first frame, another size) hold nothing: previousEmpty says so.
    gpu::FrameGraph::History color = graph.addHistory("temporalAaHistory", history.color, colorDesc);
    gpu::FrameGraph::History depth = graph.addHistory("temporalAaHistoryDepth", history.depth, depthDesc);

    TemporalAaConstants constants{frame.currentClipToPreviousClip,
                                  frame.currentClipToPreviousView,
                                  frame.worldToPreviousClip,
                                  frame.worldToPreviousView,
                                  {settings.kLowFreq, settings.kHighFreq, kSmaa2txVelocityWeight, 0.0f},
                                  {frame.historyValid && !color.previousEmpty ? 1u : 0u,
                                   frame.heldFrames, frame.framesToConverge,
                                   (frame.edgeAa ? kTemporalAaEdgeAa : 0u) |
                                       (frame.colorHasCoverage ? kTemporalAaColorHasCoverage : 0u)}};

    // 1TX's result is its accumulation; 2TX keeps the raw frame as history and resolves apart. An
    // unchanged scene runs the still's plain running mean, its own shader: lavapipe pays for both
    // sides of a branch, even a uniform one.
    const bool twoFrame = settings.mode == TemporalAaMode::Smaa2tx;
    const bool still = !twoFrame && constants.frames[0] != 0 && frame.unchanged;
    const char* variant = twoFrame ? "temporal_aa_2tx" : still ? "temporal_aa_still" : "temporal_aa";
    // A converged still keeps its mean (temporal_aa_still.comp) and reads none of the frame's
    // colour: bound in its place, the mean itself lets the frame graph cull the passes that only
    // made the colour (the lighting; SSAO still writes its history), and the render through the
    // pixel centres for the unjittered AOVs costs little more than the G-buffer.
    const bool keepsMean = still && settings.reuseConverged && frame.heldFrames >= frame.framesToConverge;
    ShaderBinding resolved = unbound();
    if (twoFrame) {
        gpu::ImageDesc resolvedDesc = colorDesc;
        resolvedDesc.usage = 0;
        resolved = storageWrite(graph.createImage("temporalAaResolved", resolvedDesc));
    }
    ComputeOutputs written = addComputePass(
        graph, {variant,
                {bufferRead(scene.buffers.camera),
                 bufferRead(graph.createBuffer("temporalAaConstants", bytesOf(constants))),
                 sampled(keepsMean ? color.previous : hdrColor),
                 sampled(gbuffer.depth), sampled(color.previous, SampledRead::Linear), sampled(depth.previous),
                 storageWrite(color.current), storageWrite(depth.current), resolved, sampled(transparentCoverage), sampled(gbuffer.instance),
                 bufferRead(scene.buffers.instances), bufferRead(scene.buffers.instanceReprojections)}});
    return written.images[twoFrame ? 2 : 0];
}

gpu::ImageHandle addTemporalAaSamplePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gbuffer,
                                         gpu::ImageHandle hdrColor, gpu::ImageHandle transparentCoverage) {
    gpu::ImageHandle sample =
        graph.createImage("temporalAaSample", imageDesc2D(kTemporalAaColorFormat, scene.width, scene.height));
    return addComputePass(graph, {"temporal_aa_sample",
                                  {sampled(hdrColor), sampled(gbuffer.depth), sampled(transparentCoverage),
                                   storageWrite(sample), bufferRead(scene.buffers.camera)}})
        .images[0];
}

}  // namespace obscura::passes
