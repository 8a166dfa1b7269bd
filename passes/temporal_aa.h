// Temporal anti-aliasing (frame step 9): SMAA 1TX (seed 000 "SMAA 1TX: a more robust temporal
// AA"), an accumulation buffer reprojected through the camera's motion, clamped to the current
// frame's neighbourhood and blended by the slide's high/low-frequency weights; or, as the
// alternative mode, the SMAA 2TX two-frame blend weighted by velocity (seed 000 "Temporal SSAA /
// SMAA 2TX/4X review"). It runs on the pre-exposed HDR light accumulation, before depth of field,
// motion blur and tone mapping; the projection is jittered by temporalAaJitter() each frame.
#pragma once

#include "gpu/history_images.h"
#include "passes/frame_resources.h"

#include <array>
#include <cstdint>

namespace obscura::passes {

enum class TemporalAaMode { Smaa1tx, Smaa2tx };

// History colour, premultiplied, with coverage in alpha: the 1TX accumulation, or 2TX's last frame.
// Accumulating 1/n of a sample needs more mantissa than B10G11R11 has (seed 004 "HDR").
constexpr VkFormat kTemporalAaColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
// A still's mean adds each of its n frames as 1/n of the frame's difference from the mean so far,
// and half floats (11-bit mantissa) round away differences below about n 2^-12 of the mean: 0.4% at
// 16 frames, 6% at 256, where the few bright samples beside an edge would vanish and the mean
// drift dark. Means of more frames than this are kept in 32-bit floats.
constexpr uint32_t kHalfFloatMeanFrames = 16;
constexpr VkFormat temporalAaHistoryFormat(uint32_t framesToConverge) {
    return framesToConverge > kHalfFloatMeanFrames ? VK_FORMAT_R32G32B32A32_SFLOAT : kTemporalAaColorFormat;
}

// The sub-pixel offset (pixels, x right and y down, each in [-0.5, 0.5)) of the projection for
// frame `index` of a cycle of `count` frames. 1TX: the first `count` points of Sobol's
// (0, 2)-sequence (x the base-2 radical inverse, y Sobol's second dimension), turned by half a
// pixel (Cranley-Patterson) so that frame 0 looks through the pixel centre: every frame after a
// reset is the unjittered image. When `count` is a power of two each of its columns and rows holds
// one offset, so an axis-aligned edge's coverage is estimated to 1/count (the Halton (2, 3)
// points before put base-3 rows: a horizontal edge's to 1/8 at 16). The rows' offsets but frame 0's are
// moved to their strata's centres (frame 0's row is the one from the pixel centre down): the
// rows' centroid is the pixel centre to 1/(2 count²). x keeps the Halton points' offsets, at their
// columns' left edges (a centroid of -1/(2 count)): a motion-blurred still pairs them with its
// shutter strata by the frame's index (shutterStratum()), and that pairing's streaks are what was
// measured (half a column more moved a 48-pixel streak's ends). 2TX: the 2x pattern of seed
// 000's SMAA 2TX (D3D's standard 2x MSAA positions, +-1/4 pixel on the diagonal).
std::array<double, 2> temporalAaJitter(TemporalAaMode mode, uint32_t index, uint32_t count);

// Frames the 2TX blend holds: the current one and the last.
constexpr uint32_t kSmaa2txFrames = 2;

// Beside the history colour: the linear view depth of the frame that wrote it (scene units, as
// SSAO keeps it) and, for 2TX, that frame's velocity length in pixels.
VkFormat temporalAaDepthFormat(TemporalAaMode mode);

// Render settings taa:mode, taa:kLowFreq, taa:kHighFreq.
struct TemporalAaSettings {
    TemporalAaMode mode;
    // The slide's weights (1TX): history weight = saturate(1 / lerp(kLowFreq, kHighFreq, w_k)).
    float kLowFreq;
    float kHighFreq;
    // A converged still's renders keep its mean without reading the frame's colour, so the frame
    // graph leaves out what only made that colour (render setting taa:reuseConverged).
    bool reuseConverged = true;
};

// What the renderer decided for this frame (renderer/temporal_accumulation.h), in the shader's
// layout: matrices column-major.
struct TemporalAaFrame {
    bool historyValid = false;  // last frame's history may be read at all
    // Nothing changed since the last frame (scene and camera): the still's running mean, no
    // reprojection, no clamp. Otherwise the history is reprojected, clamped and blended by the
    // slide's weights.
    bool unchanged = false;
    // In a still: the frames the history holds as an equal-weight mean (0 on the first frame after
    // a change: the history is not a mean of jittered frames then); this frame adds its own with
    // weight 1 / (heldFrames + 1).
    uint32_t heldFrames = 0;
    // The mean stops growing at this many frames (render setting taa:frames): a converged still.
    uint32_t framesToConverge = 1;
    // Hybrid AA drew some instance on the pixel grid (FrameScene::edgeAa): temporal pixels beside
    // one leave it out of their reprojection and clamp.
    bool edgeAa = false;
    // The frame's colour comes with its coverage in alpha (addTemporalAaSamplePass), processed
    // before the mean: a still's sample motion-blurred over its stratum of the shutter.
    bool colorHasCoverage = false;
    // This frame's clip space (jittered) to last frame's clip space (unjittered) with this frame's
    // jitter added back, so that an unchanged camera maps every pixel onto itself.
    Mat4 currentClipToPreviousClip{};
    Mat4 currentClipToPreviousView{};  // this frame's clip space to last frame's view space
    // The same from world space, for surfaces that moved on their own since (their world point is
    // first taken to where it was: InstanceReprojection).
    Mat4 worldToPreviousClip{};
    Mat4 worldToPreviousView{};
};

// The history (an explicit history input, STYLE.md, declared with FrameGraph::addHistory):
// persistent images the renderer keeps.
struct TemporalAaHistory {
    gpu::HistoryImages color;  // temporalAaHistoryFormat(frames)
    gpu::HistoryImages depth;  // temporalAaDepthFormat(mode)
};

// Returns the anti-aliased HDR colour (temporalAaHistoryFormat, coverage in alpha; in 1TX the
// history written this frame itself). `hdrColor` is the light accumulation, rendered with the
// jittered projection.
gpu::ImageHandle addTemporalAaPass(gpu::FrameGraph& graph, const FrameScene& scene,
                                   const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                   gpu::ImageHandle transparentCoverage, const TemporalAaSettings& settings,
                                   const TemporalAaFrame& frame, TemporalAaHistory& history);

// This frame's colour as temporal AA accumulates it, for passes that run on a sample before the
// mean (motion blur over a still's stratum of the shutter): the light accumulation with the
// frame's coverage in alpha, kTemporalAaColorFormat.
gpu::ImageHandle addTemporalAaSamplePass(gpu::FrameGraph& graph, const FrameScene& scene,
                                         const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                         gpu::ImageHandle transparentCoverage);

}  // namespace obscura::passes
