// The display/view transform on the GPU (seed 004 "Color grading"; Selan 2007): the OCIO
// processor baked into a 33^3 lattice behind a log2 shaper (color_lut.*), uploaded as a 3D texture
// that the tone-mapping pass reads with one filtered lookup. Rebuilt only when the request changes.
#pragma once

#include "gpu/device.h"
#include "passes/color_lut.h"

#include <optional>
#include <string>

namespace obscura::passes {

class ColorGradingLut {
public:
    // Bakes and uploads the LUT for `request` unless it is the one already held; returns the
    // reason on failure (the previous LUT stays in use).
    std::string update(gpu::Device& device, const ColorLutRequest& request);
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
