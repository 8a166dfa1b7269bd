// Histogram renormalisation (Kaplanyan 2010, slides "Color textures" and "Histogram
// renormalization"): a 16-bit colour texture whose channels each use a narrow range is stored in
// 8 bits stretched over the whole code range, and a per-channel scale and bias map the sampled
// value back. The stretch is done in linear light: 16-bit sRGB texels are decoded on the CPU
// first and the stretched values stored as linear UNORM, so filtering, mips and the affine map
// back (which commutes with filtering) all act on linear values.
#pragma once

#include "gpu/texture_upload.h"

#include <array>
#include <optional>
#include <vector>

namespace obscura::delegate {

struct Renormalized {
    gpu::MipLevel level;  // R8G8B8A8_UNORM codes t = (v - lo) / (hi - lo)
    // v = t * scale + bias per channel: scale = hi - lo, bias = lo.
    std::array<float, 4> scale{};
    std::array<float, 4> bias{};
};

// `linear` holds width x height RGBA texels of linear values in [0, 1], from a 16-bit source.
// Stretched when every channel then quantises at least as finely as the 8-bit storage it would
// otherwise have: an sRGB colour channel when its range is at most the sRGB curve's slope (linear
// per code) at its lowest value times the code range, so that the uniform step (hi - lo) / 255 is
// nowhere coarser than the sRGB step; linear channels always (the step shrinks from 1 / 255 to
// (hi - lo) / 255). nullopt otherwise: the texture is stored as sRGB 8-bit as before.
std::optional<Renormalized> renormalize(uint32_t width, uint32_t height, const std::vector<float>& linear,
                                        bool srgbColor);

}  // namespace obscura::delegate
