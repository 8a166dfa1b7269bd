// The sample pattern of the SSAO obscurance pass (shaders/ssao_obscurance.comp), built here so that
// the unit tests check exactly what the shader reads from its push constants.
#pragma once

#include <array>
#include <cstdint>

namespace obscura::passes {

// Seed 004 "SSAO improvements": volumetric obscurance (Loos & Sloan 2010) with 4 samples, taken as
// two point-symmetric pairs (+offset and -offset). Offsets are in units of the sphere's radius, in
// the plane through the centre perpendicular to the view axis.
struct SsaoPixelSamples {
    std::array<float, 2> inner;  // first pair, in the inner half (by area) of the disc
    std::array<float, 2> outer;  // second pair, in the outer half
};

// The pattern repeats over 4x4 blocks of half-resolution pixels (interleaved sampling, Keller &
// Heidrich 2001): the 16 pixels of a block together take 64 well-spread samples, and the blur,
// which spans a block, averages them.
constexpr uint32_t kSsaoPatternSide = 4;
using SsaoPattern = std::array<SsaoPixelSamples, kSsaoPatternSide * kSsaoPatternSide>;

// Indexed by (y mod 4) * 4 + (x mod 4) of the half-resolution pixel.
SsaoPattern ssaoSamplePattern();

// GLSL packSnorm4x8(inner.x, inner.y, outer.x, outer.y) of every pixel: the shader's push constants.
// Eight bits are plenty: the shader snaps each sample to a texel anyway.
std::array<uint32_t, kSsaoPatternSide * kSsaoPatternSide> packSsaoSamplePattern(const SsaoPattern& pattern);

}  // namespace obscura::passes
