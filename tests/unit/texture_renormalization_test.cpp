// Histogram renormalisation (Kaplanyan 2010, "Histogram renormalization"): a low-contrast 16-bit
// texture stored in 8 bits quantises with steps of its range / 255 instead of 1 / 255.
#include "delegate/texture_image.h"
#include "delegate/texture_renormalization.h"
#include "harness/image/png_io.h"
#include "tests/support/usdz_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace obscura::delegate {
namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// The value a sampler returns for texel i, mapped back by the renormalisation.
float restored(const Renormalized& r, size_t i) {
    return float(std::to_integer<int>(r.level.bytes[i])) / 255.0f * r.scale[i % 4] + r.bias[i % 4];
}

TEST(Renormalization, LowContrastQuantisesToItsRangeOverTheCodes) {
    // A dense linear gradient over [0.40, 0.46] in every colour channel: stored as 8-bit codes of
    // the value its error reaches half a step, 1 / 510; stretched, half a step of the range,
    // 0.06 / 510, some 17 times smaller.
    constexpr float kLo = 0.40f, kHi = 0.46f;
    constexpr uint32_t kWidth = 4096;
    std::vector<float> linear;
    for (uint32_t x = 0; x < kWidth; ++x) {
        const float v = kLo + (kHi - kLo) * float(x) / float(kWidth - 1);
        linear.insert(linear.end(), {v, v, v, 1.0f});
    }
    auto stretched = renormalize(kWidth, 1, linear, false);
    ASSERT_TRUE(stretched);
    float before = 0.0f, after = 0.0f;
    for (size_t i = 0; i < linear.size(); ++i) {
        if (i % 4 == 3) continue;
        before = std::max(before, std::abs(std::round(linear[i] * 255.0f) / 255.0f - linear[i]));
        after = std::max(after, std::abs(restored(*stretched, i) - linear[i]));
    }
    EXPECT_LE(after, (kHi - kLo) / 255.0f / 2.0f + 1e-6f);
    EXPECT_GE(before, 0.9f / 255.0f / 2.0f);  // the gradient meets nearly the worst rounding
    EXPECT_NEAR(stretched->scale[0], kHi - kLo, 1e-6f);
    EXPECT_NEAR(stretched->bias[0], kLo, 1e-6f);
    // A constant channel (alpha) keeps its value with a scale of 0.
    EXPECT_EQ(stretched->scale[3], 0.0f);
    EXPECT_EQ(restored(*stretched, 3), 1.0f);
}

TEST(Renormalization, WideSrgbRangeStaysWhereSrgbIsFiner) {
    // Black to white in linear light: a uniform step of 1 / 255 is coarser than the sRGB curve's
    // near black (1 / (12.92 * 255)), so the texture keeps 8-bit sRGB storage.
    std::vector<float> linear;
    for (int x = 0; x < 256; ++x) linear.insert(linear.end(), {float(x) / 255.0f, float(x) / 255.0f, float(x) / 255.0f, 1.0f});
    EXPECT_FALSE(renormalize(256, 1, linear, true));
    EXPECT_TRUE(renormalize(256, 1, linear, false));  // linear data never loses by stretching
}

class RenormalizedFile : public ::testing::Test {
protected:
    RenormalizedFile() {
        dir_ = std::filesystem::temp_directory_path() / ("obscura_renormalization_" + std::to_string(getpid()));
        std::filesystem::create_directories(dir_);
    }
    ~RenormalizedFile() override { std::filesystem::remove_all(dir_); }
    // The bytes of a 16-bit RGB PNG of a horizontal gradient of sRGB codes lo..hi in every channel.
    std::string writeGradient(const std::string& name, float lo, float hi, int width) {
        std::vector<uint16_t> rgb;
        for (int x = 0; x < width; ++x) {
            const auto code = uint16_t(std::lround((lo + (hi - lo) * float(x) / float(width - 1)) * 65535.0f));
            rgb.insert(rgb.end(), {code, code, code});
        }
        std::string path = (dir_ / name).string();
        EXPECT_FALSE(image::isError(image::writePng16(path, width, 1, rgb.data())));
        codes_ = rgb;
        return test::fileBytes(path);
    }
    std::filesystem::path dir_;
    std::vector<uint16_t> codes_;
};

TEST_F(RenormalizedFile, SrgbSixteenBitFileIsStretchedInLinearLight) {
    // sRGB codes 0.40..0.46 are linear 0.133..0.178: renormalised, the linear error is at most half
    // of (0.178 - 0.133) / 255, where 8-bit sRGB storage errs by up to half its step, about
    // 0.70 / 255 at code 0.40 (the curve's slope there).
    constexpr int kWidth = 4096;
    const std::string file = writeGradient("low_contrast.png", 0.40f, 0.46f, kWidth);
    auto decoded = decodeTextureImage(file, SourceColorSpace::Auto, TextureRole::Material);
    ASSERT_TRUE(std::holds_alternative<TextureImage>(decoded)) << std::get<std::string>(decoded);
    const TextureImage& image = std::get<TextureImage>(decoded);
    EXPECT_EQ(image.format, VK_FORMAT_R8G8B8A8_UNORM);
    ASSERT_TRUE(image.renormalised());
    const float range = srgbToLinear(0.46f) - srgbToLinear(0.40f);
    float before = 0.0f, after = 0.0f;
    for (int x = 0; x < kWidth; ++x) {
        const float encoded = float(codes_[size_t(x) * 3]) / 65535.0f, exact = srgbToLinear(encoded);
        before = std::max(before, std::abs(srgbToLinear(std::round(encoded * 255.0f) / 255.0f) - exact));
        const float t = float(std::to_integer<int>(image.level0.bytes[size_t(x) * 4])) / 255.0f;
        after = std::max(after, std::abs(t * image.renormScale[0] + image.renormBias[0] - exact));
    }
    EXPECT_LE(after, range / 255.0f / 2.0f + 1e-6f);
    EXPECT_GT(before, 0.6f / 255.0f / 2.0f);
}

TEST_F(RenormalizedFile, DomeTexturesAndWideRangesKeepEightBitSrgb) {
    const std::string narrow = writeGradient("narrow.png", 0.40f, 0.46f, 64);
    auto plain = decodeTextureImage(narrow, SourceColorSpace::Auto, TextureRole::Plain);
    ASSERT_TRUE(std::holds_alternative<TextureImage>(plain));
    EXPECT_FALSE(std::get<TextureImage>(plain).renormalised());
    EXPECT_EQ(std::get<TextureImage>(plain).format, VK_FORMAT_R8G8B8A8_SRGB);
    const std::string wide = writeGradient("wide.png", 0.0f, 1.0f, 64);
    auto material = decodeTextureImage(wide, SourceColorSpace::Auto, TextureRole::Material);
    ASSERT_TRUE(std::holds_alternative<TextureImage>(material));
    EXPECT_FALSE(std::get<TextureImage>(material).renormalised());
    EXPECT_EQ(std::get<TextureImage>(material).format, VK_FORMAT_R8G8B8A8_SRGB);
}

}  // namespace
}  // namespace obscura::delegate
