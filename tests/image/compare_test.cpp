// Image comparison metrics against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "harness/image/compare.h"

namespace obscura::image {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A picture with smooth and sharp detail, so blur and noise both change its structure.
Image pattern(int w, int h, std::vector<std::string> channels = {"R", "G", "B"}) {
    Image img = Image::make(w, h, std::move(channels));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float values[4] = {
                0.5f + 0.4f * std::sin(0.3f * static_cast<float>(x)) *
                           std::cos(0.2f * static_cast<float>(y)),
                ((x / 8 + y / 8) % 2 == 0) ? 0.2f : 0.8f,
                static_cast<float>(x) / static_cast<float>(w),
                1.0f,
            };
            for (int c = 0; c < static_cast<int>(img.channelCount()); ++c) {
                img.at(x, y, c) = values[c % 4];
            }
        }
    }
    return img;
}

Image filled(int w, int h, float value, std::vector<std::string> channels = {"R", "G", "B"}) {
    Image img = Image::make(w, h, std::move(channels));
    std::fill(img.pixels.begin(), img.pixels.end(), value);
    return img;
}

CompareMetrics compareOk(const Image& a, const Image& b, const CompareOptions& options = {}) {
    const Result<CompareMetrics> r = compare(a, b, options);
    EXPECT_FALSE(isError(r)) << errorOf(r);
    return isError(r) ? CompareMetrics{} : std::get<CompareMetrics>(r);
}

Image withNoise(const Image& img, float sigma, unsigned seed) {
    Image noisy = img;
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, sigma);
    for (float& v : noisy.pixels) v += noise(rng);
    return noisy;
}

Image boxBlurred(const Image& img) {
    Image out = img;
    for (int y = 1; y + 1 < img.height; ++y) {
        for (int x = 1; x + 1 < img.width; ++x) {
            for (int c = 0; c < static_cast<int>(img.channelCount()); ++c) {
                float sum = 0.0f;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) sum += img.at(x + dx, y + dy, c);
                }
                out.at(x, y, c) = sum / 9.0f;
            }
        }
    }
    return out;
}

TEST(Compare, IdenticalImagesArePerfect) {
    const Image a = pattern(40, 30);
    const CompareMetrics m = compareOk(a, a);
    EXPECT_EQ(m.psnr, kInf);
    EXPECT_EQ(m.ssim, 1.0);
    EXPECT_EQ(m.maxAbsError, 0.0);
    EXPECT_EQ(m.meanAbsError, 0.0);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.width, 40);
    EXPECT_EQ(m.height, 30);
}

TEST(Compare, ConstantOffsetGivesAnalyticPsnr) {
    // Values and offset are binary fractions, so every difference is exactly 1/16.
    Image a = Image::make(16, 16, {"R", "G", "B"});
    for (size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = static_cast<float>(i % 128) / 256.0f;
    Image b = a;
    for (float& v : b.pixels) v += 0.0625f;
    const double mse = 0.0625 * 0.0625;
    const CompareMetrics m = compareOk(a, b);
    EXPECT_DOUBLE_EQ(m.psnr, 10.0 * std::log10(1.0 / mse));  // 24.08 dB
    EXPECT_DOUBLE_EQ(m.rmse, 0.0625);
    EXPECT_DOUBLE_EQ(m.maxAbsError, 0.0625);
    EXPECT_DOUBLE_EQ(m.meanAbsError, 0.0625);
}

TEST(Compare, AlphaCountsOnlyWhenBothImagesHaveIt) {
    const Image a = filled(8, 8, 0.25f, {"R", "G", "B", "A"});
    Image b = filled(8, 8, 0.5f, {"R", "G", "B", "A"});
    for (size_t i = 3; i < b.pixels.size(); i += 4) b.pixels[i] = 0.25f;  // equal alpha
    // One channel in four is equal: mse = 3/4 * 0.25^2.
    EXPECT_DOUBLE_EQ(compareOk(a, b).psnr, 10.0 * std::log10(1.0 / (0.75 * 0.0625)));

    const Image rgb = filled(8, 8, 0.5f);
    EXPECT_DOUBLE_EQ(compareOk(a, rgb).psnr, 10.0 * std::log10(1.0 / 0.0625));
}

TEST(Compare, MaxAndMeanErrorsAreExact) {
    // 2x2 RGB, twelve differences: 0, 1/2, 1/4, 0, 1/8, 0, 0, 0, 3/4, 0, 0, 1/16.
    const Image a = filled(2, 2, 0.0f);
    Image b = a;
    b.pixels = {0.0f, 0.5f, 0.25f, 0.0f, -0.125f, 0.0f, 0.0f, 0.0f, 0.75f, 0.0f, 0.0f, 0.0625f};
    const CompareMetrics m = compareOk(a, b);
    EXPECT_EQ(m.maxAbsError, 0.75);
    EXPECT_EQ(m.meanAbsError, (0.5 + 0.25 + 0.125 + 0.75 + 0.0625) / 12.0);
    const double sumSquared = 0.25 + 0.0625 + 0.015625 + 0.5625 + 0.00390625;
    EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(sumSquared / 12.0));
}

TEST(Compare, ChosenChannelsOnly) {
    Image a = filled(4, 4, 1.0f, {"R", "G", "B", "Z"});
    Image b = a;
    b.at(1, 1, 0) = 0.0f;  // R differs, Z does not
    const CompareMetrics z = compareOk(a, b, {{"Z"}});
    EXPECT_EQ(z.maxAbsError, 0.0);
    EXPECT_EQ(z.ssim, 1.0);
    EXPECT_EQ(compareOk(a, b, {{"R"}}).maxAbsError, 1.0);
}

TEST(Compare, SsimOfFlatImagesMatchesTheFormula) {
    // With no variance SSIM reduces to the luminance term (2 mx my + C1) / (mx^2 + my^2 + C1).
    const double x = 0.5;
    const double y = static_cast<double>(0.6f);
    const double c1 = 0.01 * 0.01;
    const CompareMetrics m = compareOk(filled(20, 20, 0.5f), filled(20, 20, 0.6f));
    EXPECT_NEAR(m.ssim, (2 * x * y + c1) / (x * x + y * y + c1), 1e-9);
}

TEST(Compare, SsimFallsAsNoiseGrows) {
    const Image a = pattern(64, 48);
    double previous = 1.0;
    for (float sigma : {0.01f, 0.03f, 0.1f, 0.3f}) {
        const double ssim = compareOk(a, withNoise(a, sigma, 7)).ssim;
        EXPECT_LT(ssim, previous) << "sigma " << sigma;
        EXPECT_GE(ssim, 0.0);
        previous = ssim;
    }
    EXPECT_GT(compareOk(a, withNoise(a, 0.01f, 7)).ssim, 0.9);
}

TEST(Compare, SsimOfBlurredCopyIsBelowOne) {
    const Image a = pattern(64, 48);
    const double ssim = compareOk(a, boxBlurred(a)).ssim;
    EXPECT_LT(ssim, 0.999);
    EXPECT_GT(ssim, 0.5);
}

TEST(Compare, SsimClampsHdrValues) {
    // Both clamp to white: structurally identical, though far apart in value (PSNR below 0 dB).
    const CompareMetrics m = compareOk(filled(16, 16, 5.0f), filled(16, 16, 3.0f));
    EXPECT_EQ(m.ssim, 1.0);
    EXPECT_DOUBLE_EQ(m.psnr, 10.0 * std::log10(1.0 / 4.0));
}

TEST(Compare, SmallImagesShrinkTheWindow) {
    const Image a = pattern(5, 3);
    EXPECT_EQ(compareOk(a, a).ssim, 1.0);
    const double ssim = compareOk(a, withNoise(a, 0.1f, 3)).ssim;
    EXPECT_LT(ssim, 1.0);
    EXPECT_TRUE(std::isfinite(ssim));
    EXPECT_EQ(compareOk(filled(1, 1, 0.5f), filled(1, 1, 0.5f)).ssim, 1.0);
}

TEST(Compare, NaNFailsButEqualInfinitiesMatch) {
    Image a = filled(4, 4, 0.5f, {"R", "G", "B", "Z"});
    for (size_t i = 3; i < a.pixels.size(); i += 4) {
        a.pixels[i] = std::numeric_limits<float>::infinity();  // depth background
    }
    Image b = a;
    EXPECT_EQ(compareOk(a, b, {{"Z"}}).psnr, kInf);

    b.at(2, 2, 1) = std::numeric_limits<float>::quiet_NaN();
    const CompareMetrics m = compareOk(a, b);
    EXPECT_TRUE(std::isnan(m.maxAbsError));
    EXPECT_TRUE(std::isnan(m.psnr));
    EXPECT_TRUE(std::isnan(m.ssim));
}

TEST(Compare, SizeMismatchIsAnError) {
    const Result<CompareMetrics> r = compare(pattern(10, 10), pattern(10, 11));
    ASSERT_TRUE(isError(r));
    EXPECT_NE(errorOf(r).find("10x10 vs 10x11"), std::string::npos) << errorOf(r);
    EXPECT_TRUE(isError(makeDiffImage(pattern(10, 10), pattern(11, 10))));
}

TEST(Compare, MissingChannelIsAnError) {
    const Image rgb = pattern(4, 4);
    const Image rg = filled(4, 4, 0.0f, {"R", "G"});
    const Result<CompareMetrics> r = compare(rgb, rg);
    ASSERT_TRUE(isError(r));
    EXPECT_NE(errorOf(r).find("'B'"), std::string::npos) << errorOf(r);

    const Result<CompareMetrics> n = compare(rgb, rgb, {{"normal.X"}});
    ASSERT_TRUE(isError(n));
    EXPECT_NE(errorOf(n).find("normal.X"), std::string::npos) << errorOf(n);
}

TEST(DiffImage, ScalesByTenAndClamps) {
    const Image a = filled(2, 1, 0.5f);
    Image b = a;
    b.pixels = {0.5f, 0.51f, 0.45f, 0.0f, 0.5f, 1.0f};
    const Result<Image> r = makeDiffImage(a, b);
    ASSERT_FALSE(isError(r)) << errorOf(r);
    const Image& diff = std::get<Image>(r);
    EXPECT_EQ(diff.channels, (std::vector<std::string>{"R", "G", "B"}));
    ASSERT_EQ(diff.width, 2);
    ASSERT_EQ(diff.height, 1);
    EXPECT_EQ(diff.at(0, 0, 0), 0.0f);
    EXPECT_NEAR(diff.at(0, 0, 1), 0.1f, 1e-5f);
    EXPECT_NEAR(diff.at(0, 0, 2), 0.5f, 1e-5f);
    EXPECT_EQ(diff.at(1, 0, 0), 1.0f);
    EXPECT_EQ(diff.at(1, 0, 1), 0.0f);
    EXPECT_EQ(diff.at(1, 0, 2), 1.0f);
}

TEST(DiffImage, AlphaAndSingleChannelDifferencesShowGrey) {
    const Image a = filled(1, 1, 0.5f, {"R", "G", "B", "A", "Z"});
    Image b = a;
    b.at(0, 0, 3) = 0.52f;  // alpha only
    b.at(0, 0, 4) = 0.45f;  // Z only
    const Image alpha = std::get<Image>(makeDiffImage(a, b));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(alpha.at(0, 0, c), 0.2f, 1e-5f);
    const Image z = std::get<Image>(makeDiffImage(a, b, {{"Z"}}));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(z.at(0, 0, c), 0.5f, 1e-5f);
}

}  // namespace
}  // namespace obscura::image
