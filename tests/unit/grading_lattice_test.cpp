// Interpolation between the grading chart's lattice points (pass_support/grading_lattice.h): both ways
// reproduce the lattice at its points and an identity lattice everywhere; tetrahedral keeps greys
// neutral under a grade that keeps greys neutral, which trilinear does not.
#include "pass_support/grading_lattice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

namespace obscura::passes {
namespace {

using Rgb = std::array<float, 3>;

GradingLattice latticeOf(uint32_t size, const std::function<Rgb(Rgb)>& grade) {
    GradingLattice lattice{size, {}};
    for (uint32_t b = 0; b < size; ++b)
        for (uint32_t g = 0; g < size; ++g)
            for (uint32_t r = 0; r < size; ++r)
                lattice.values.push_back(grade({r / float(size - 1), g / float(size - 1), b / float(size - 1)}));
    return lattice;
}

// A grade that leaves greys as they are: chroma about the Rec.709 luminance raised by a gain that
// grows with the chroma (a linear gain would be reproduced exactly by either interpolation).
Rgb saturate(Rgb c) {
    const float y = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
    float chroma = 0.0f;
    for (int i = 0; i < 3; ++i) chroma = std::max(chroma, std::abs(c[i] - y));
    Rgb out;
    for (int i = 0; i < 3; ++i) out[i] = std::clamp(y + (c[i] - y) * (1.0f + 8.0f * chroma), 0.0f, 1.0f);
    return out;
}

constexpr LatticeInterpolation kBoth[] = {LatticeInterpolation::Trilinear, LatticeInterpolation::Tetrahedral};

TEST(GradingLattice, IdentityLatticeIsTheIdentityEverywhere) {
    const GradingLattice identity = latticeOf(16, [](Rgb c) { return c; });
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (LatticeInterpolation interpolation : kBoth)
        for (int i = 0; i < 1000; ++i) {
            Rgb c{unit(random), unit(random), unit(random)};
            Rgb got = sampleLattice(identity, c, interpolation);
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], c[ch], 1e-6f);
        }
}

TEST(GradingLattice, LatticePointsAreReproducedAndInputIsClamped) {
    const GradingLattice graded = latticeOf(16, saturate);
    for (LatticeInterpolation interpolation : kBoth) {
        for (uint32_t b = 0; b < 16; b += 5)
            for (uint32_t g = 0; g < 16; g += 3)
                for (uint32_t r = 0; r < 16; ++r) {
                    Rgb got = sampleLattice(graded, {r / 15.0f, g / 15.0f, b / 15.0f}, interpolation);
                    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], graded.at(r, g, b)[ch], 1e-6f);
                }
        Rgb below = sampleLattice(graded, {-1.0f, 2.0f, 0.0f}, interpolation);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(below[ch], graded.at(0, 15, 0)[ch], 1e-6f);
    }
}

TEST(GradingLattice, TetrahedralKeepsGreysNeutralWhereTrilinearTintsThem) {
    const GradingLattice graded = latticeOf(16, saturate);
    double worst[2] = {0.0, 0.0};
    for (int i = 0; i <= 1000; ++i) {
        const float v = i / 1000.0f;
        for (int k = 0; k < 2; ++k) {
            Rgb got = sampleLattice(graded, {v, v, v}, kBoth[k]);
            for (int ch = 0; ch < 3; ++ch) worst[k] = std::max(worst[k], double(std::abs(got[ch] - v)));
        }
    }
    // Off the lattice, trilinear blends the cell's non-grey corners, whose graded values need not
    // cancel; tetrahedral takes greys from the two grey corners alone.
    std::printf("[ metric ] chroma gain on a 16^3 lattice, worst grey error: trilinear %.5f, tetrahedral %.7f\n",
                worst[0], worst[1]);
    EXPECT_LT(worst[1], 1e-6);

    // Colours between the lattice points: both against the exact grade, printed.
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    double mean[2] = {0.0, 0.0};
    const int samples = 20000;
    for (int i = 0; i < samples; ++i) {
        Rgb c{unit(random), unit(random), unit(random)};
        Rgb exact = saturate(c);
        for (int k = 0; k < 2; ++k) {
            Rgb got = sampleLattice(graded, c, kBoth[k]);
            for (int ch = 0; ch < 3; ++ch) mean[k] += std::abs(got[ch] - exact[ch]) / (3.0 * samples);
        }
    }
    std::printf("[ metric ] chroma gain, mean error over random colours: trilinear %.5f, tetrahedral %.5f\n",
                mean[0], mean[1]);
}

}  // namespace
}  // namespace obscura::passes
