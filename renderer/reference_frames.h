// The reference mode's sub-frames (DESIGN.md "Testing and measuring": accumulation of jittered
// lens, shutter and pixel sub-frames as ground truth): where each one samples the aperture, the
// shutter interval and the pixel.
#pragma once

#include "renderer/pixel_filter.h"
#include "pass_support/thin_lens.h"

#include <array>
#include <cstdint>
#include <vector>

namespace obscura::renderer {

struct ReferenceSubFrame {
    std::array<double, 2> aperture;     // on the unit aperture (x right, y up), passes::sampleAperture
    double shutter;                     // fraction of the shutter interval, [0, 1)
    std::array<double, 2> pixelJitter;  // pixels: [-0.5, 0.5)^2 for the box of width 1, else distributed as the filter
    std::array<double, 2> emitter;      // [0, 1)^2: the point of each light's emitter (emitterSample)
};

// `count` deterministic, stratified sub-frames: the aperture from a Hammersley set ((k + 0.5) / N
// and the base-2 radical inverse) over the square, mapped with the same concentric + n-gon mapping
// as the depth-of-field taps; the shutter from a golden-ratio rank-1 lattice (each 1/N of the
// interval once); the jitter from the radical inverses in bases 3 and 5, the lights' emitters from
// those in bases 7 and 11 (Halton), so no dimension repeats another's pattern; the jitter then
// warped to the pixel filter (PixelFilterWarp).
std::vector<ReferenceSubFrame> referenceSubFrames(uint32_t count, const passes::ApertureShape& aperture,
                                                  const PixelFilter& filter = {});

// The stratum of the shutter sample `index` of `count` takes, in [0, count): the golden-ratio
// rank-1 lattice above, shared by the reference's sub-frames and a still's accumulated frames
// (TemporalAaStep::shutterStratum), so that both sample the shutter alike.
uint32_t shutterStratum(uint32_t index, uint32_t count);

// The sub-pixel jitter (pixels, x right, y down) of a still's frame `index` of `count` under the box
// filter of width 1, `samples` MSAA samples a pixel resolved over its box
// (passes::SampleResolve::PixelBox). Vulkan's standard
// sample locations are N-rooks: their x lie 1/samples apart. A jitter within a strip 1/samples wide
// and the pixel tall so moves each sample across its own column of the pixel (wrapping around its
// box), all of them together across the whole pixel. The frames' jitters are a Hammersley set over
// the strip (x the base-2 radical inverse, y k / count, both centred in their strata): for count =
// 2^m a (0, m, 2)-net,
// whose count x samples points fall one in each of as many equal cells of the pixel (an 8 x 8 grid
// for 16 frames of 4 samples), where the plain jitter left the pattern's own gaps and clumps.
std::array<double, 2> pixelBoxJitter(uint32_t index, uint32_t count, uint32_t samples);

// The sub-pixel jitter (pixels, in [-0.5, 0.5)) of frame `index` of the `count` a still's mean
// counts (TemporalAccumulation; with strata of the lens and shutter or without): the Hammersley set (x the base-2 radical inverse, y index / count) turned by
// half a pixel in both axes, so that frame 0, the first after a reset, looks through the pixel
// centre. Every row 1/count of the pixel tall holds one point, and for count = 2^m every column
// too (a (0, m, 2)-net: the turn by a half maps dyadic cells onto dyadic cells), so a
// near-horizontal or near-vertical edge's coverage errs by one stratum at most; the real-time
// Halton points' y, base 3, leaves rows of the pixel empty and others doubled.
std::array<double, 2> stillPixelJitter(uint32_t index, uint32_t count);

// The cells of the aperture `count` accumulated frames of a still look through: count / 2 for an
// even count, each looked through by two frames, frames 2c and 2c + 1, whose pixel jitters are
// apart (stillPixelJitter: the base-2 radical inverses of 2c and 2c + 1 differ by half a pixel).
// A point smaller than a pixel is seen by one pixel centre per frame, and each frame carries what
// it saw into its own cell alone: two coverage samples per cell lower the variance of the cell's
// share (bright-point bokeh, DepthOfFieldConvergence tests at 160x90, against the 1024-sub-frame
// reference: 36.9 -> 37.5 dB round, 36.8 -> 37.3 dB with 6 blades), at the cost of cells twice as
// large for the post-process to span (planes 45.0 -> 42.7 and 44.6 -> 42.8 dB). The bokeh is the
// nearer to its bar. An odd count has a cell per frame.
uint32_t stillLensCells(uint32_t count);

// The part of the aperture a still's accumulated frame `index` of `count` looks through
// (TemporalAaStep::lensStratum): cell j of a rows x columns grid over the square before the
// aperture mapping (rows the largest divisor of the cell count up to its square root), so that
// the cells partition the aperture, each 1/stillLensCells(count) of its area (the mapping
// preserves area). The frame looks from the cell centre's point of the aperture (`position`, as
// ReferenceSubFrame::aperture) and its depth of field spreads it over the rest of the cell: the
// cells' kernels add up to the whole aperture's. The cells are visited in the order of a rank-1
// lattice whose multiplier (near 0.7549 N, the plastic ratio, and sharing no factor with N)
// differs from the shutter's, so that a frame's lens position does not follow its time in the
// shutter.
struct StillLensSample {
    std::array<double, 2> position;
    passes::ApertureCell cell;
};
StillLensSample stillLensSample(uint32_t index, uint32_t count, const passes::ApertureShape& aperture);

}  // namespace obscura::renderer
