// Temporal anti-aliasing from frame to frame (passes/temporal_aa.h): whether the history may be
// reused, which sub-pixel jitter a frame takes, how its pixels map onto last frame's, and when a
// still image has converged. Bookkeeping only, no GPU: the delegate asks it once per frame.
#pragma once

#include "renderer/matrix.h"
#include "renderer/pixel_filter.h"
#include "passes/temporal_aa.h"

#include <array>
#include <optional>
#include <string>

namespace obscura::renderer {

// What a frame's history was rendered with. Any difference resets the history, as hdEmbree
// restarts its accumulation: a camera cut (another camera prim), a resize, a render setting
// changed (the settings' version counter).
struct TemporalAaKey {
    std::string camera;
    uint32_t width = 0;
    uint32_t height = 0;
    uint64_t settingsVersion = 0;
    bool operator==(const TemporalAaKey&) const = default;
};

struct TemporalAaStep {
    passes::TemporalAaFrame pass;       // for addTemporalAaPass
    std::array<double, 2> jitter{};     // pixels, x right, y down
    Matrix4d clipJitter = kIdentity;    // applied after the camera's projection: clip x += 2 jitter_x / width * w ...
    // The jitter's index in its cycle of framesToConverge: noise that turns with it (the shadow
    // filter's taps) is integrated by a still's mean like the jitter.
    uint32_t noiseFrame = 0;
    // The still's mean counts this frame (1TX): its MSAA samples resolve linearly
    // (passes::SampleResolve), its jitter follows the pixel filter.
    bool stillSample = false;
    // Another render of the unchanged scene would add nothing: the accumulation holds taa:frames
    // frames (1TX) or both frames (2TX), and (1TX) this frame looked through the pixel centres, so
    // the depth, normal and id AOVs are the unjittered ones.
    bool converged = false;
    // Motion blur in a 1TX still (the shutter open): each frame the mean counts samples the
    // shutter as the reference's sub-frames do, one stratum of taa:frames each (the fractions
    // [start, end] of the shutter, shutterStratum()); its own motion blur spans the stratum alone
    // and runs before the mean, which so converges to the shutter's integral whatever the streak's
    // length. None: the frame is seen at the shutter's centre and blurred over the whole shutter
    // after temporal AA (a real-time frame: the first after a reset or any change, which the
    // mean does not count), unless the mean it keeps already holds every stratum
    // (shutterAccumulated: a settled still).
    std::optional<std::array<double, 2>> shutterStratum;
    bool shutterAccumulated = false;
    // Depth of field in a 1TX still (a lens that blurs): each frame the mean counts looks through
    // its own cell of the aperture, as the reference's sub-frames do: cell `lensStratum` of
    // taa:frames (stillLensSample()), its own depth of field spanning the cell alone and
    // run before the mean, which so converges to the lens's integral, the diaphragm's shape
    // included. None: the frame looks through the lens's centre and the post-process blurs over
    // the whole aperture after temporal AA (a real-time frame), unless the mean already holds
    // every stratum (lensAccumulated: a settled still).
    std::optional<uint32_t> lensStratum;
    bool lensAccumulated = false;
};

// What a still samples besides the pixel.
struct StillSampling {
    bool shutter = false;  // the shutter is open and motionBlur on: strata of the shutter
    bool lens = false;     // the lens blurs (dof on, an aperture): strata of the aperture
    // The frames the still's mean counts take their offsets distributed as this filter; frames of
    // a changing scene keep the plain jitter within the pixel.
    PixelFilter filter;
    // MSAA samples a frame resolves over the pixel's box (passes::SampleResolve::PixelBox): the
    // frames the still's mean counts take pixelBoxJitter() instead; 0: none.
    uint32_t pixelBoxSamples = 0;
};

class TemporalAccumulation {
public:
    // `sceneVersion`: the delegate's counter of prim insertions, removals and dirty marks (the
    // camera's among them); when it moved, the history is reprojected and blended by the slide's
    // weights rather than averaged. `frames`: taa:frames. `view` and `projection`: the camera's,
    // unjittered (row-vector convention), at the shutter's centre.
    TemporalAaStep next(const TemporalAaKey& key, uint64_t sceneVersion, passes::TemporalAaMode mode, uint32_t frames,
                        const Matrix4d& view, const Matrix4d& projection, const StillSampling& sampling = {});
    // Temporal AA is off: the next frame starts afresh.
    void reset() { last_.reset(); }

private:
    std::optional<TemporalAaKey> last_;
    Matrix4d lastView_ = kIdentity;
    Matrix4d lastProjection_ = kIdentity;
    uint64_t lastSceneVersion_ = 0;
    uint64_t frame_ = 0;  // frames since the history was reset: the jitter sequence's index
    uint32_t held_ = 0;   // frames the history holds as an equal-weight mean
};

}  // namespace obscura::renderer
