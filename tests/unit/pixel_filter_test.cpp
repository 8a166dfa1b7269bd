// The pixel filter's offsets against the filters themselves: equally weighted offsets drawn
// through PixelFilterWarp have the filter's distribution. Each filter's variance is integrated
// here from its textbook formula (Cycles' definitions), independently of the warp's table.
#include "renderer/pixel_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace obscura::renderer {
namespace {

// The variance of the density proportional to `f` over [-w/2, w/2], by the midpoint rule.
double variance(const std::function<double(double)>& f, double w) {
    constexpr int kSteps = 100000;
    double mass = 0.0, second = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        double v = ((i + 0.5) / kSteps - 0.5) * w;
        mass += f(v);
        second += f(v) * v * v;
    }
    return second / mass;
}

// Offsets of u on an even grid over [-0.5, 0.5): their mean and variance.
std::array<double, 2> offsetMoments(const PixelFilter& filter) {
    PixelFilterWarp warp(filter);
    constexpr int kCount = 4096;
    double mean = 0.0, second = 0.0;
    for (int i = 0; i < kCount; ++i) {
        double o = warp.offset((i + 0.5) / kCount - 0.5);
        EXPECT_LE(std::fabs(o), 0.5 * filter.width + 1e-12);
        mean += o / kCount;
        second += o * o / kCount;
    }
    return {mean, second - mean * mean};
}

TEST(PixelFilter, BoxSpansItsWidth) {
    PixelFilterWarp unit({PixelFilterKind::Box, 1.0});
    EXPECT_EQ(unit.offset(-0.5), -0.5);
    EXPECT_EQ(unit.offset(0.25), 0.25) << "the box of width 1 leaves temporal AA's jitter as it is";
    auto [mean, var] = offsetMoments({PixelFilterKind::Box, 2.0});
    EXPECT_NEAR(mean, 0.0, 1e-9);
    EXPECT_NEAR(var, 4.0 / 12.0, 1e-4);
}

TEST(PixelFilter, GaussianAndBlackmanHarrisHaveTheirVariance) {
    for (double width : {1.5, 3.0}) {
        PixelFilter gaussian{PixelFilterKind::Gaussian, width};
        auto g = offsetMoments(gaussian);
        double gTruth = variance([&](double v) { double x = v * 6.0 / width; return std::exp(-2.0 * x * x); }, width);
        EXPECT_NEAR(gTruth, std::pow(width / 12.0, 2), 1e-3 * gTruth) << "sigma = width / 12";
        EXPECT_NEAR(g[0], 0.0, 1e-6);
        EXPECT_NEAR(g[1], gTruth, 0.01 * gTruth) << width;
        PixelFilter bh{PixelFilterKind::BlackmanHarris, width};
        auto b = offsetMoments(bh);
        double bTruth = variance(
            [&](double v) {
                double x = 2.0 * std::numbers::pi * (v / width + 0.5);
                return 0.35875 - 0.48829 * std::cos(x) + 0.14128 * std::cos(2.0 * x) - 0.01168 * std::cos(3.0 * x);
            },
            width);
        EXPECT_NEAR(b[0], 0.0, 1e-6);
        EXPECT_NEAR(b[1], bTruth, 0.01 * bTruth) << width;
        std::printf("width %.1f: gaussian variance %.5f (filter %.5f), blackman-harris %.5f (filter %.5f)\n", width,
                    g[1], gTruth, b[1], bTruth);
        EXPECT_EQ(PixelFilterWarp(gaussian).offset(0.0), 0.0) << "the first frame looks through the centre";
    }
}

TEST(PixelFilter, TokensName) {
    EXPECT_EQ(pixelFilterKind("gaussian"), PixelFilterKind::Gaussian);
    EXPECT_EQ(pixelFilterKind("blackman-harris"), PixelFilterKind::BlackmanHarris);
    EXPECT_EQ(pixelFilterKind("box"), PixelFilterKind::Box);
}

}  // namespace
}  // namespace obscura::renderer
