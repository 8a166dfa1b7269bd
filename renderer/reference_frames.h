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
    std::array<double, 2> aperture;  // on the unit aperture (x right, y up), passes::sampleAperture
    double shutter;                  // fraction of the shutter interval, [0, 1)
    // Pixels: [-0.5, 0.5)^2 for the box of width 1, else distributed as the filter; with several
    // samples a pixel, x within a strip 1/samples wide (pixelBoxJitter).
    std::array<double, 2> pixelJitter;
    std::array<double, 2> emitter;  // [0, 1)^2: the point of each light's emitter (emitterSample)
};

// How many MSAA samples each reference sub-frame takes in a pixel under `filter`: four under the
// box of width 1, resolved over the pixel's box (passes::SampleResolve::PixelBox), where a
// sub-frame of one sample sees a point smaller than a pixel through at most a few pixel centres
// and the reference's own noise is of the size of the fidelity bars it measures (a 1.5-pixel
// emitter's bokeh: 41 dB between 1024 and 4096 one-sample sub-frames); one under any other
// filter, whose jitter is warped to the filter's distribution.
uint32_t referenceSamples(const PixelFilter& filter);

// `count` deterministic, stratified sub-frames: the aperture from a Hammersley set ((k + 0.5) / N
// and the base-2 radical inverse) over the square, mapped with the same concentric + n-gon mapping
// as the depth-of-field taps; the shutter from a golden-ratio rank-1 lattice (each 1/N of the
// interval once); the jitter from the radical inverses in bases 3 and 5, the lights' emitters from
// those in bases 7 and 11 (Halton), so no dimension repeats another's pattern; the jitter then
// warped to the pixel filter (PixelFilterWarp), or with `samples` > 1 (the box filter only) its x
// narrowed to the strip each sample sweeps its own column of the pixel in (pixelBoxJitter).
std::vector<ReferenceSubFrame> referenceSubFrames(uint32_t count, const passes::ApertureShape& aperture,
                                                  const PixelFilter& filter = {}, uint32_t samples = 1);

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

// The cells of the aperture `count` accumulated frames of a still look through: count / 2 for an
// even count, each looked through by two frames, frames 2c and 2c + 1, whose pixel jitters are
// far apart (the base-2 radical inverses of 2c and 2c + 1 differ by half a pixel, the base-3 ones
// by about a third). A point smaller than a pixel is seen by one pixel centre per frame, and each
// frame carries what it saw into its own cell alone: two coverage samples per cell halve the
// variance of the cell's share (bright-point bokeh, DepthOfFieldConvergence tests at 160x90:
// 36.5 -> 38.3 dB round, 36.7 -> 37.9 dB with 6 blades, against the 1024-sub-frame reference),
// at the cost of cells twice as large for the post-process to span (planes 44.0 -> 43.1 and
// 43.7 -> 42.5 dB; four frames per cell: bokeh 37.8, planes 40.8). An odd count has a cell per frame.
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
