// The SSAO sample pattern (pass_support/ssao_pattern.h), checked as the obscurance shader decodes it from
// its push constants: 4 samples per pixel in two point-symmetric pairs, and over a 4x4 block of
// pixels 64 samples that cover the disc evenly in angle and in area.
#include "pass_support/ssao_pattern.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

namespace obscura::passes {
namespace {

constexpr double kPi = std::numbers::pi;

struct Sample {
    double x, y;
    bool inner;
};

// GLSL unpackSnorm4x8: byte i (least significant first) as int8, over 127, clamped to [-1, 1].
std::array<double, 4> unpackSnorm4x8(uint32_t packed) {
    std::array<double, 4> v{};
    for (int i = 0; i < 4; ++i) v[i] = std::clamp(int8_t(uint8_t(packed >> (8 * i))) / 127.0, -1.0, 1.0);
    return v;
}

// The four samples of each pixel as the shader sees them: +-inner, +-outer.
std::vector<std::vector<Sample>> decodedSamples() {
    std::vector<std::vector<Sample>> pixels;
    for (uint32_t packed : packSsaoSamplePattern(ssaoSamplePattern())) {
        auto v = unpackSnorm4x8(packed);
        pixels.push_back({{v[0], v[1], true}, {-v[0], -v[1], true}, {v[2], v[3], false}, {-v[2], -v[3], false}});
    }
    return pixels;
}

double angleOf(const Sample& s) {
    double a = std::atan2(s.y, s.x);
    return a < 0.0 ? a + 2.0 * kPi : a;
}

TEST(SsaoPattern, PackingKeepsTheOffsetsToHalfAStep) {
    SsaoPattern pattern = ssaoSamplePattern();
    auto packed = packSsaoSamplePattern(pattern);
    for (size_t i = 0; i < pattern.size(); ++i) {
        auto v = unpackSnorm4x8(packed[i]);
        const double expected[4] = {pattern[i].inner[0], pattern[i].inner[1], pattern[i].outer[0], pattern[i].outer[1]};
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(v[c], expected[c], 0.5 / 127.0 + 1e-6) << "pixel " << i << " component " << c;
    }
}

TEST(SsaoPattern, FourSamplesPerPixelInsideTheSphere) {
    for (const auto& pixel : decodedSamples()) {
        ASSERT_EQ(pixel.size(), 4u);
        for (const Sample& s : pixel) {
            double r = std::hypot(s.x, s.y);
            // Strictly inside: every sample has a chord of the sphere to integrate along.
            EXPECT_LT(r, 1.0);
            EXPECT_GT(std::sqrt(1.0 - r * r), 0.1);
        }
    }
}

TEST(SsaoPattern, BlockCoversEveryDirectionOncePerPairKind) {
    // 32 equal sectors of the full turn; a pixel's pairs are point-symmetric, so the 16 inner pairs
    // of a block can put exactly one sample in each sector, and so can the 16 outer ones.
    constexpr int kSectors = 32;
    std::array<int, kSectors> inner{}, outer{};
    for (const auto& pixel : decodedSamples())
        for (const Sample& s : pixel) {
            int sector = int(angleOf(s) / (2.0 * kPi / kSectors)) % kSectors;
            ++(s.inner ? inner : outer)[sector];
        }
    for (int i = 0; i < kSectors; ++i) {
        EXPECT_EQ(inner[i], 1) << "sector " << i;
        EXPECT_EQ(outer[i], 1) << "sector " << i;
    }
}

TEST(SsaoPattern, BlockCoversEveryEqualAreaRingOnce) {
    // The disc in 32 rings of equal area (r^2 in steps of 1/32): inner pairs fill the 16 rings of
    // the inner half one each, outer pairs the outer half.
    std::set<int> rings;
    for (const auto& pixel : decodedSamples())
        for (int pair = 0; pair < 2; ++pair) {
            const Sample& s = pixel[pair * 2];
            int ring = int((s.x * s.x + s.y * s.y) * 32.0);
            EXPECT_EQ(ring < 16, s.inner) << "ring " << ring;
            EXPECT_TRUE(rings.insert(ring).second) << "ring " << ring << " taken twice";
        }
    EXPECT_EQ(rings.size(), 32u);
}

TEST(SsaoPattern, NeighbouringPixelsSampleFarApartDirections) {
    // Any 2x2 window of the tiled pattern holds inner pairs from all four quarters of a half turn,
    // so the blur's neighbours complement each other even near edges where it drops taps.
    auto pixels = decodedSamples();
    for (uint32_t y = 0; y < kSsaoPatternSide; ++y)
        for (uint32_t x = 0; x < kSsaoPatternSide; ++x) {
            std::set<int> quarters;
            for (uint32_t dy = 0; dy < 2; ++dy)
                for (uint32_t dx = 0; dx < 2; ++dx) {
                    uint32_t index = ((y + dy) % kSsaoPatternSide) * kSsaoPatternSide + (x + dx) % kSsaoPatternSide;
                    double halfTurn = std::fmod(angleOf(pixels[index][0]), kPi);
                    quarters.insert(int(halfTurn / (kPi / 4.0)));
                }
            EXPECT_EQ(quarters.size(), 4u) << "window at (" << x << ", " << y << ")";
        }
}

TEST(SsaoPattern, PairsOfAPixelAreAQuarterTurnApart) {
    for (const auto& pixel : decodedSamples()) {
        double dot = pixel[0].x * pixel[2].x + pixel[0].y * pixel[2].y;
        double cosine = dot / (std::hypot(pixel[0].x, pixel[0].y) * std::hypot(pixel[2].x, pixel[2].y));
        EXPECT_NEAR(cosine, 0.0, 0.05);
    }
}

}  // namespace
}  // namespace obscura::passes
