// Seed 004 "Color grading" (Selan 2007): the display/view transform baked into a shaper + 3D LUT
// must reproduce OpenColorIO's own evaluation, and the built-in config's views must be what they
// claim (sRGB encoding, identity, a bounded monotonic filmic curve).
#include "pass_support/color_lut.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>

namespace obscura::passes {
namespace {

using Rgb = std::array<float, 3>;

// Tests control $OCIO themselves: an $OCIO in the developer's environment must not change which
// config "" means.
class ColorLutTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (const char* value = std::getenv("OCIO")) saved_ = value;
        unsetenv("OCIO");
    }
    void TearDown() override {
        if (saved_) setenv("OCIO", saved_->c_str(), 1);
        else unsetenv("OCIO");
    }

private:
    std::optional<std::string> saved_;
};

ColorLut bake(const ColorLutRequest& request, uint32_t size = 33) {
    auto result = bakeColorLut(request, size);
    if (auto* error = std::get_if<std::string>(&result)) ADD_FAILURE() << *error;
    return std::holds_alternative<ColorLut>(result) ? std::get<ColorLut>(result) : ColorLut{};
}

Rgb view(const ColorLutRequest& request, Rgb linear) {
    auto result = applyViewTransform(request, linear);
    if (auto* error = std::get_if<std::string>(&result)) ADD_FAILURE() << *error;
    return std::holds_alternative<Rgb>(result) ? std::get<Rgb>(result) : Rgb{};
}

std::string bakeError(const ColorLutRequest& request) {
    auto result = bakeColorLut(request);
    return std::holds_alternative<std::string>(result) ? std::get<std::string>(result) : "(no error)";
}

float clamp01(float v) { return std::clamp(v, 0.0f, 1.0f); }

// What the GPU does: shaper per channel, a trilinear fetch (texel centres on the lattice), clamp.
Rgb sampleTrilinear(const ColorLut& lut, Rgb linear) {
    const float last = float(lut.size - 1);
    std::array<uint32_t, 3> base;
    std::array<float, 3> frac;
    for (int c = 0; c < 3; ++c) {
        const float x = shaperEncode(linear[c], lut) * last;
        base[c] = std::min(uint32_t(x), lut.size - 2);
        frac[c] = x - float(base[c]);
    }
    Rgb result = {0, 0, 0};
    for (uint32_t corner = 0; corner < 8; ++corner) {
        float weight = 1.0f;
        size_t index = 0, stride = 1;
        for (int c = 0; c < 3; ++c) {
            const uint32_t bit = (corner >> c) & 1u;
            weight *= bit ? frac[c] : 1.0f - frac[c];
            index += (base[c] + bit) * stride;
            stride *= lut.size;
        }
        for (int c = 0; c < 3; ++c) result[c] += weight * lut.rgba[index * 4 + c];
    }
    for (float& value : result) value = clamp01(value);
    return result;
}

float srgbEncode(float linear) {
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float luminance(Rgb rgb) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

// The largest per-channel difference between the baked LUT and the processor over 1000 random
// scene-linear colours, log-uniform per channel in [1e-3, 64].
float maxLutError(const ColorLutRequest& request, uint32_t size) {
    const ColorLut lut = bake(request, size);
    if (lut.rgba.empty()) return INFINITY;
    std::mt19937 random(4);
    std::uniform_real_distribution<float> stops(std::log2(1e-3f), std::log2(64.0f));
    float maxError = 0.0f;
    for (int i = 0; i < 1000; ++i) {
        const Rgb linear = {std::exp2(stops(random)), std::exp2(stops(random)), std::exp2(stops(random))};
        const Rgb expected = view(request, linear);
        const Rgb actual = sampleTrilinear(lut, linear);
        for (int c = 0; c < 3; ++c) maxError = std::max(maxError, std::abs(actual[c] - clamp01(expected[c])));
    }
    return maxError;
}

TEST(ColorLutShaper, RoundTripsAndIsMonotonic) {
    const ColorLut lut;
    float previous = -1.0f;
    const int steps = 20000;
    for (int i = 0; i <= steps; ++i) {
        const float linear = std::pow(10.0f, -4.0f + 8.0f * float(i) / steps);
        const float coordinate = shaperEncode(linear, lut);
        ASSERT_GT(coordinate, previous) << "at " << linear;
        ASSERT_LE(coordinate, 1.0f);
        EXPECT_NEAR(shaperDecode(coordinate, lut), linear, 1e-5f * linear) << "at " << linear;
        previous = coordinate;
    }
    EXPECT_EQ(shaperEncode(0.0f, lut), 0.0f);
    EXPECT_EQ(shaperEncode(-1.0f, lut), 0.0f);
    EXPECT_EQ(shaperEncode(1e6f, lut), 1.0f);
    EXPECT_NEAR(shaperEncode(kShaperMiddleGrey, lut), -lut.shaperMinStops / (lut.shaperMaxStops - lut.shaperMinStops),
                1e-6f);
}

TEST(ColorLutShaper, ToeJoinsTheLogSegmentSmoothly) {
    const ColorLut lut;
    const float range = lut.shaperMaxStops - lut.shaperMinStops;
    const float toeEnd = 1.0f / (range * std::log(2.0f));
    const float below = shaperDecode(toeEnd - 1e-4f, lut), at = shaperDecode(toeEnd, lut),
                above = shaperDecode(toeEnd + 1e-4f, lut);
    // C1: the two one-sided slopes agree to first order.
    EXPECT_NEAR((at - below) / (above - at), 1.0f, 2e-3f);
    EXPECT_NEAR(shaperDecode(0.5f * toeEnd, lut), 0.5f * at, 1e-6f * at);  // the toe is linear through 0
}

TEST_F(ColorLutTest, BuiltInViewsAreListed) {
    EXPECT_EQ(builtInViews(), (std::vector<std::string>{"Filmic", "Standard", "Raw"}));
}

TEST_F(ColorLutTest, BakedLayoutIsRedFastest) {
    const ColorLutRequest request{.view = "Standard"};
    const ColorLut lut = bake(request, 9);
    ASSERT_EQ(lut.rgba.size(), size_t(9 * 9 * 9 * 4));
    EXPECT_EQ(lut.description, "config: built-in, display: sRGB, view: Standard, look: none");
    for (float value : lut.rgba) ASSERT_TRUE(std::isfinite(value));
    // Texel (r, g, b) = (1, 4, 7) holds the view of the decoded lattice point.
    const uint32_t r = 1, g = 4, b = 7;
    const size_t texel = (r + 9 * (g + 9 * b)) * 4;
    const Rgb expected = view(request, {shaperDecode(r / 8.0f, lut), shaperDecode(g / 8.0f, lut),
                                        shaperDecode(b / 8.0f, lut)});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(lut.rgba[texel + c], expected[c], 1e-6f);
    EXPECT_EQ(lut.rgba[texel + 3], 1.0f);
}

TEST_F(ColorLutTest, DefaultsAreTheFilmicView) {
    EXPECT_EQ(bake({}, 2).description, "config: built-in, display: sRGB, view: Filmic, look: none");
}

// Tolerances measured (max over 1000 colours; see the printed values) and set with ~2x margin.
TEST_F(ColorLutTest, TrilinearLookupMatchesTheProcessor) {
    struct Case {
        const char* view;
        float tolerance33, tolerance65;
    };
    for (const Case& c : {Case{"Filmic", 0.05f, 0.05f}, Case{"Standard", 0.012f, 0.004f}, Case{"Raw", 0.06f, 0.02f}}) {
        const ColorLutRequest request{.view = c.view};
        const float error33 = maxLutError(request, 33), error65 = maxLutError(request, 65);
        std::printf("%-8s max |LUT - OCIO|: 33^3 %.6f, 65^3 %.6f\n", c.view, error33, error65);
        RecordProperty(std::string(c.view) + "_max_error_33", std::to_string(error33));
        RecordProperty(std::string(c.view) + "_max_error_65", std::to_string(error65));
        EXPECT_LT(error33, c.tolerance33) << c.view;
        EXPECT_LT(error65, c.tolerance65) << c.view;
    }
}

TEST_F(ColorLutTest, StandardIsTheSrgbEncoding) {
    const ColorLutRequest request{.display = "sRGB", .view = "Standard"};
    for (float value : view(request, {0.18f, 0.18f, 0.18f})) EXPECT_NEAR(value, 0.4613f, 0.002f);
    for (float value : view(request, {1.0f, 1.0f, 1.0f})) EXPECT_NEAR(value, 1.0f, 1e-4f);
    // Above white the encoding goes on; the lookup clamps.
    for (float value : view(request, {4.0f, 4.0f, 4.0f})) EXPECT_NEAR(value, srgbEncode(4.0f), 1e-3f);
    for (float value : sampleTrilinear(bake(request), {4.0f, 4.0f, 4.0f})) EXPECT_EQ(value, 1.0f);
    const Rgb coloured = view(request, {0.5f, 0.05f, 0.002f});
    EXPECT_NEAR(coloured[0], srgbEncode(0.5f), 1e-3f);
    EXPECT_NEAR(coloured[1], srgbEncode(0.05f), 1e-3f);
    EXPECT_NEAR(coloured[2], srgbEncode(0.002f), 1e-3f);
}

TEST_F(ColorLutTest, RawIsIdentity) {
    const ColorLutRequest request{.view = "Raw"};
    for (Rgb linear : {Rgb{0, 0, 0}, Rgb{0.18f, 0.5f, 1.0f}, Rgb{0.001f, 0.9f, 0.3f}}) {
        const Rgb out = view(request, linear);
        for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[c], linear[c]);
    }
}

TEST_F(ColorLutTest, FilmicIsMonotonicAndBounded) {
    const ColorLutRequest request{.view = "Filmic"};
    for (float value : view(request, {0, 0, 0})) EXPECT_NEAR(value, 0.0f, 1e-3f);
    // Exposure ramps 2^-12 .. 2^18. OCIO 2.1's built-in output transform has no final clamp: greys
    // creep past white by a few percent (1.04 at 1e4) and saturated colours leave the sRGB gamut
    // (ACES limits to AP1); the lookup's clamp makes both white / the gamut edge on screen.
    for (Rgb tint : {Rgb{1, 1, 1}, Rgb{1.0f, 0.6f, 0.3f}, Rgb{0.2f, 0.4f, 1.0f}}) {
        const bool grey = tint == Rgb{1, 1, 1};
        float previous = -1.0f;
        for (int i = 0; i <= 300; ++i) {
            const float exposure = std::exp2(-12.0f + 0.1f * float(i));
            const Rgb out = view(request, {tint[0] * exposure, tint[1] * exposure, tint[2] * exposure});
            for (float value : out) ASSERT_TRUE(!grey || value <= 1.05f) << value << " at exposure " << exposure;
            ASSERT_GE(luminance(out), previous) << "exposure " << exposure;
            previous = luminance(out);
        }
        EXPECT_TRUE(!grey || previous > 0.99f) << "white is reached, got " << previous;
    }
    const ColorLut lut = bake(request);
    for (float value : sampleTrilinear(lut, {0, 0, 0})) EXPECT_NEAR(value, 0.0f, 1e-3f);
    for (float value : sampleTrilinear(lut, {1e4f, 1e4f, 1e4f})) EXPECT_EQ(value, 1.0f);
    // A tone curve, not a clip: mid grey lands mid-range and 4.0 is still below white.
    EXPECT_NEAR(view(request, {0.18f, 0.18f, 0.18f})[1], 0.39f, 0.05f);
    EXPECT_LT(view(request, {4.0f, 4.0f, 4.0f})[1], 0.99f);
}

TEST_F(ColorLutTest, UnknownNamesListTheValidChoices) {
    const std::string displayError = bakeError({.display = "P3"});
    EXPECT_NE(displayError.find("display 'P3'"), std::string::npos) << displayError;
    EXPECT_NE(displayError.find("valid displays: sRGB"), std::string::npos) << displayError;
    const std::string viewError = bakeError({.view = "Log"});
    EXPECT_NE(viewError.find("view 'Log'"), std::string::npos) << viewError;
    EXPECT_NE(viewError.find("valid views: Filmic, Standard, Raw"), std::string::npos) << viewError;
    const std::string lookError = bakeError({.look = "Contrast"});
    EXPECT_NE(lookError.find("look 'Contrast'"), std::string::npos) << lookError;
    EXPECT_NE(lookError.find("valid looks: (none)"), std::string::npos) << lookError;
}

TEST_F(ColorLutTest, MissingConfigFileIsNamed) {
    const std::string path = "/nonexistent/obscura/config.ocio";
    const std::string error = bakeError({.configPath = path});
    EXPECT_NE(error.find(path), std::string::npos) << error;
    setenv("OCIO", path.c_str(), 1);
    const std::string fromEnvironment = bakeError({});
    EXPECT_NE(fromEnvironment.find(path), std::string::npos) << fromEnvironment;
    EXPECT_NE(fromEnvironment.find("$OCIO"), std::string::npos) << fromEnvironment;
}

// A small config of our own: scene_linear, an sRGB display whose view is OCIO's sRGB curve
// (ExponentWithLinearTransform), and a look that doubles the exposure with an ASC CDL slope of 2.
constexpr const char* kTestConfig = R"(ocio_profile_version: 2
name: obscura-test
roles:
  scene_linear: linear
  default: linear
displays:
  sRGB:
    - !<View> {name: Curve, colorspace: srgb_encoded}
    - !<View> {name: Raw, colorspace: linear}
looks:
  - !<Look>
    name: Bright
    process_space: linear
    transform: !<CDLTransform> {slope: [2, 2, 2]}
colorspaces:
  - !<ColorSpace>
    name: linear
  - !<ColorSpace>
    name: srgb_encoded
    from_scene_reference: !<ExponentWithLinearTransform>
      gamma: [2.4, 2.4, 2.4, 1]
      offset: [0.055, 0.055, 0.055, 0]
      direction: inverse
)";

std::string writeTestConfig(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("obscura_color_lut_" + std::to_string(getpid()) + "_" + name);
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / "config.ocio";
    std::ofstream(path) << kTestConfig;
    return path.string();
}

TEST_F(ColorLutTest, ConfigFileLoadsFromPathAndEnvironment) {
    const std::string path = writeTestConfig("path_and_env");
    const ColorLutRequest fromPath{.configPath = path};
    EXPECT_EQ(bake(fromPath, 2).description, "config: obscura-test, display: sRGB, view: Curve, look: none");
    EXPECT_NEAR(view(fromPath, {0.18f, 0.18f, 0.18f})[0], srgbEncode(0.18f), 1e-4f);

    setenv("OCIO", path.c_str(), 1);
    EXPECT_EQ(bake({}, 2).description, "config: obscura-test, display: sRGB, view: Curve, look: none");
    EXPECT_NEAR(view({}, {0.05f, 0.05f, 0.05f})[2], srgbEncode(0.05f), 1e-4f);
    std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST_F(ColorLutTest, CdlLookScalesBeforeTheView) {
    const std::string path = writeTestConfig("look");
    const ColorLutRequest plain{.configPath = path}, bright{.configPath = path, .look = "Bright"};
    const Rgb linear = {0.02f, 0.1f, 0.3f};
    const Rgb before = view(plain, linear), after = view(bright, linear);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(before[c], srgbEncode(linear[c]), 1e-4f);
        EXPECT_NEAR(after[c], srgbEncode(2.0f * linear[c]), 1e-4f);  // CDL: out = in * slope
    }
    const ColorLut lut = bake(bright, 33);
    EXPECT_EQ(lut.description, "config: obscura-test, display: sRGB, view: Curve, look: Bright");
    const Rgb sampled = sampleTrilinear(lut, linear);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sampled[c], after[c], 0.008f);

    const std::string error = bakeError({.configPath = path, .look = "Bright, Dim"});
    EXPECT_NE(error.find("look 'Dim'"), std::string::npos) << error;
    EXPECT_NE(error.find("valid looks: Bright"), std::string::npos) << error;
    std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

}  // namespace
}  // namespace obscura::passes
