#include "pass_support/ssao_pattern.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::passes {
namespace {

// Ordered-dither (Bayer) ranks of a 4x4 block: any 2x2 window holds ranks from all four quarters
// of 0..15, so neighbouring pixels sample far-apart directions.
constexpr std::array<uint32_t, 16> kBayerRank = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};

// Van der Corput radical inverse in base 2 over 4 bits: with the rank as the other coordinate,
// the 16 pixels form a Hammersley point set (angle, area), stratified in both.
uint32_t reverseFourBits(uint32_t v) {
    return ((v & 1u) << 3) | ((v & 2u) << 1) | ((v & 4u) >> 1) | ((v & 8u) >> 3);
}

int8_t snorm8(float v) {
    return int8_t(std::lround(std::clamp(v, -1.0f, 1.0f) * 127.0f));
}

}  // namespace

SsaoPattern ssaoSamplePattern() {
    constexpr uint32_t count = kSsaoPatternSide * kSsaoPatternSide;
    SsaoPattern pattern{};
    for (uint32_t pixel = 0; pixel < count; ++pixel) {
        uint32_t rank = kBayerRank[pixel];
        // A pair covers the angle and its opposite, so ranks spread the pairs over half a turn; the
        // outer pair is a quarter turn from the inner one.
        double angle = (rank + 0.5) * std::numbers::pi / count;
        // Equal-area strata: radius = sqrt(area fraction), inner pairs in [0, 1/2) of the disc's
        // area, outer ones in [1/2, 1); the outer stratum runs the other way so that a pixel with a
        // short inner pair gets a long outer one.
        double stratum = (reverseFourBits(rank) + 0.5) / count;
        double innerRadius = std::sqrt(0.5 * stratum);
        double outerRadius = std::sqrt(0.5 + 0.5 * (1.0 - stratum));
        double c = std::cos(angle), s = std::sin(angle);
        pattern[pixel].inner = {float(innerRadius * c), float(innerRadius * s)};
        pattern[pixel].outer = {float(-outerRadius * s), float(outerRadius * c)};
    }
    return pattern;
}

std::array<uint32_t, kSsaoPatternSide * kSsaoPatternSide> packSsaoSamplePattern(const SsaoPattern& pattern) {
    std::array<uint32_t, kSsaoPatternSide * kSsaoPatternSide> packed{};
    for (size_t i = 0; i < pattern.size(); ++i) {
        const float components[4] = {pattern[i].inner[0], pattern[i].inner[1], pattern[i].outer[0],
                                     pattern[i].outer[1]};
        // packSnorm4x8: the first component in the least significant byte.
        for (uint32_t c = 0; c < 4; ++c) packed[i] |= uint32_t(uint8_t(snorm8(components[c]))) << (8 * c);
    }
    return packed;
}

}  // namespace obscura::passes
