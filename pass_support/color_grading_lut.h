// The display/view transform on the GPU (seed 004 "Color grading"; Selan 2007): the OCIO
// processor baked into a 33^3 lattice behind a log2 shaper (color_lut.*), uploaded as a 3D texture
// that the tone-mapping pass reads with one filtered lookup. Rebuilt only when the request changes.
// An artist's grade (grading_lattice.h) follows the view: it maps the view's display values, so
// it is composed into the same lattice and the frame still pays one lookup.
#pragma once

#include "gpu/frame_backend.h"
#include "pass_support/color_lut.h"
#include "pass_support/grading_lattice.h"

#include <optional>
#include <string>

namespace obscura::passes {

// An artist's grade of the view's display values.
struct DisplayGrade {
    const GradingLattice* lattice = nullptr;  // none: the view alone
    LatticeInterpolation interpolation = LatticeInterpolation::Trilinear;
    std::string key;  // names the lattice's contents (the chart file and its version)
};

class ColorGradingLut {
public:
    // Bakes and uploads the LUT for `request` (then `grade`) unless it is the one already held;
    // returns the reason on failure (the previous LUT stays in use).
    std::string update(gpu::FrameBackend& backend, const ColorLutRequest& request, const DisplayGrade& grade = {});
    const gpu::ImagePtr& texture() const { return texture_; }
    const ColorLut& lut() const { return lut_; }

private:
    std::optional<std::string> key_;
    ColorLut lut_;
    gpu::ImagePtr texture_;
};

// IEEE half from float, round to nearest even (the LUT texture is RGBA16F: signed, filterable
// everywhere, and holding the unclamped lattice values the lookup clamps after filtering).
uint16_t floatToHalf(float value);

}  // namespace obscura::passes
