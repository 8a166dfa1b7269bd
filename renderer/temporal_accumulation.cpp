#include "renderer/temporal_accumulation.h"

#include "renderer/reference_frames.h"

#include <algorithm>

namespace obscura::renderer {

TemporalAaStep TemporalAccumulation::next(const TemporalAaKey& key, uint64_t sceneVersion, passes::TemporalAaMode mode,
                                          uint32_t frames, const Matrix4d& view, const Matrix4d& projection,
                                          const StillSampling& sampling) {
    const bool twoFrame = mode == passes::TemporalAaMode::Smaa2tx;
    const uint32_t framesToConverge = twoFrame ? passes::kSmaa2txFrames : std::max(frames, 1u);
    const bool valid = last_ && *last_ == key;
    const bool sceneChanged = sceneVersion != lastSceneVersion_;
    const bool shutterStrata = sampling.shutter && !twoFrame;
    const bool lensStrata = sampling.lens && !twoFrame;
    // Either kind of stratum makes the first frame after a reset the real-time one, which the mean
    // does not count.
    const bool strata = shutterStrata || lensStrata;
    frame_ = valid ? frame_ + 1 : 0;

    TemporalAaStep step;
    step.pass.historyValid = valid;
    step.pass.framesToConverge = framesToConverge;
    // A settled 1TX still (the mean is complete and nothing changed) keeps its colour and looks
    // through the pixel centres.
    const bool settled = valid && !sceneChanged && held_ >= framesToConverge && !twoFrame;
    const bool sample = valid && !sceneChanged && !settled;
    // A still's samples of the shutter take the jitter offsets (and the shadow filter's turns) in
    // the order the mean counts them, as a still without motion blur does from its reset on: an
    // unmoving pixel accumulates the same values in the same order, bit for bit.
    step.noiseFrame = uint32_t(frame_ % framesToConverge);
    if (strata && sample) step.noiseFrame = held_;
    // The frames the mean counts: the samples, and the first after a reset where no stratum
    // makes it the real-time one.
    step.stillSample = !twoFrame && (sample || (!valid && !strata));
    if (!settled) {
        step.jitter = passes::temporalAaJitter(mode, step.noiseFrame, framesToConverge);
        if (step.stillSample) {
            PixelFilterWarp warp(sampling.filter);
            step.jitter = {warp.offset(step.jitter[0]), warp.offset(step.jitter[1])};
            if (sampling.pixelBoxSamples > 0)
                step.jitter = pixelBoxJitter(step.noiseFrame, framesToConverge, sampling.pixelBoxSamples);
        }
    }
    if (shutterStrata && sample) {
        double start = double(shutterStratum(held_, framesToConverge));
        step.shutterStratum = std::array<double, 2>{start / framesToConverge, (start + 1.0) / framesToConverge};
    }
    step.shutterAccumulated = shutterStrata && settled;
    if (lensStrata && sample) step.lensStratum = held_;
    step.lensAccumulated = lensStrata && settled;
    // The mean counts proper samples only: the first frame after a reset is one (its own jittered
    // image), but a frame of change leaves the reprojected, clamped blend, whose 1/n share of the
    // still's mean would outweigh the converged error; the still after it starts the mean afresh.
    // With motion blur or depth of field the first frame after a reset is no sample either: it is
    // the real-time frame, blurred over the whole shutter and the whole aperture.
    step.pass.unchanged = valid && !sceneChanged;
    if (!valid || sceneChanged) {
        step.pass.heldFrames = 0;
        held_ = valid || strata ? 0 : 1;
    } else {
        step.pass.heldFrames = held_;
        held_ = std::min(held_ + 1, framesToConverge);
    }
    step.converged = held_ >= framesToConverge && !step.shutterStratum && !step.lensStratum &&
                     (twoFrame || (step.jitter[0] == 0.0 && step.jitter[1] == 0.0));

    step.clipJitter[12] = 2.0 * step.jitter[0] / key.width;
    step.clipJitter[13] = 2.0 * step.jitter[1] / key.height;
    if (valid) {
        // The G-buffer was rendered with the jittered projection; last frame's image is taken
        // unjittered, then this frame's jitter is added back: an unchanged camera maps every pixel
        // onto itself, whichever offsets the two frames had.
        Matrix4d currentClipToWorld = kIdentity;
        invert(multiply(view, multiply(projection, step.clipJitter)), currentClipToWorld);
        step.pass.currentClipToPreviousClip = toFloats<passes::Mat4>(
            multiply(currentClipToWorld, multiply(multiply(lastView_, lastProjection_), step.clipJitter)));
        step.pass.currentClipToPreviousView = toFloats<passes::Mat4>(multiply(currentClipToWorld, lastView_));
        step.pass.worldToPreviousClip =
            toFloats<passes::Mat4>(multiply(multiply(lastView_, lastProjection_), step.clipJitter));
        step.pass.worldToPreviousView = toFloats<passes::Mat4>(lastView_);
    } else {
        step.pass.currentClipToPreviousClip = step.pass.currentClipToPreviousView = step.pass.worldToPreviousClip =
            step.pass.worldToPreviousView = toFloats<passes::Mat4>(kIdentity);
    }
    last_ = key;
    lastView_ = view;
    lastProjection_ = projection;
    lastSceneVersion_ = sceneVersion;
    return step;
}

}  // namespace obscura::renderer
