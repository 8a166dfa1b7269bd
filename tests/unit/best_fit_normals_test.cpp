// Seed 004 appendix A: best-fit normals quantise with less error than plain normalised 8-bit
// storage, measured on a dense set of directions.
#include "pass_support/best_fit_normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace obscura::passes {
namespace {

double angleBetween(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    double d = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
    return std::acos(std::clamp(d, -1.0, 1.0));
}

TEST(BestFitNormals, QuantisationErrorBelowNormalizedStorage) {
    // A Fibonacci sphere: 200k nearly uniform directions.
    const int n = 200000;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    double sumBest = 0, sumPlain = 0, maxBest = 0, maxPlain = 0;
    for (int i = 0; i < n; ++i) {
        double y = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - y * y), phi = golden * i;
        std::array<float, 3> dir = {float(r * std::cos(phi)), float(y), float(r * std::sin(phi))};
        double best = angleBetween(dir, decodeNormal(encodeBestFitNormal(dir)));
        double plain = angleBetween(dir, decodeNormal(encodeNormalizedNormal(dir)));
        sumBest += best;
        sumPlain += plain;
        maxBest = std::max(maxBest, best);
        maxPlain = std::max(maxPlain, plain);
    }
    double meanBest = sumBest / n, meanPlain = sumPlain / n;
    RecordProperty("mean_error_best_fit_deg", std::to_string(meanBest * 180 / std::numbers::pi));
    RecordProperty("mean_error_normalized_deg", std::to_string(meanPlain * 180 / std::numbers::pi));
    std::printf("mean angular error: best fit %.5f deg, normalised %.5f deg; max %.5f vs %.5f deg\n",
                meanBest * 180 / std::numbers::pi, meanPlain * 180 / std::numbers::pi, maxBest * 180 / std::numbers::pi,
                maxPlain * 180 / std::numbers::pi);
    EXPECT_LT(meanBest, meanPlain / 4.0);
    EXPECT_LT(maxBest, maxPlain);
}

TEST(BestFitNormals, TheBuiltTableHoldsTheSearchsScales) {
    // The library embeds the table a build step wrote; every texel it holds must be what the
    // appendix's search gives (a sparse grid plus the table's edges, which the clamp touches).
    std::span<const uint16_t> table = bestFitScaleTable();
    ASSERT_EQ(table.size(), size_t(kBestFitTableSize) * kBestFitTableSize);
    std::vector<uint32_t> coordinates{0, 1, kBestFitTableSize / 2, kBestFitTableSize - 2, kBestFitTableSize - 1};
    for (uint32_t c = 3; c < kBestFitTableSize; c += 61) coordinates.push_back(c);
    for (uint32_t j : coordinates)
        for (uint32_t i : coordinates)
            ASSERT_EQ(table[size_t(j) * kBestFitTableSize + i], bestFitTableEntry(i, j)) << "texel " << i << ", " << j;
}

TEST(BestFitNormals, ScaleKeepsTheLargestComponentInRange) {
    for (float t : {0.0f, 0.3f, 0.7f}) {
        float scale = findBestFitScale({1.0f, t, t * 0.5f});
        EXPECT_GT(scale, 0.0f);
        EXPECT_LE(scale, 1.0f);
    }
}

TEST(BestFitNormals, AxisDirectionsKeepTheirFullScale) {
    // 0 has no exact 8-bit UNORM code (127.5), so axes carry half a step of error in the two
    // minor components; the fit must keep the full scale that makes that error smallest.
    for (auto dir : {std::array<float, 3>{1, 0, 0}, {0, -1, 0}, {0, 0, 1}}) {
        double best = angleBetween(dir, decodeNormal(encodeBestFitNormal(dir)));
        double plain = angleBetween(dir, decodeNormal(encodeNormalizedNormal(dir)));
        EXPECT_LE(best, plain + 1e-9);
        EXPECT_LT(best, 1.5 / 127.5);
    }
}

}  // namespace
}  // namespace obscura::passes
