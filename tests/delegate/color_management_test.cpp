// The display AOV goes through the OCIO view transform baked into a 3D LUT: compared with OCIO's
// own CPU processor on colours the accumulation format stores exactly.
#include "harness/image/png_io.h"
#include "pass_support/color_lut.h"
#include "tests/delegate/render_fixture.h"
#include "tests/support/grading_chart_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

namespace obscura::test {
namespace {

struct EmissivePlane {
    TestHost host;
    explicit EmissivePlane(std::array<float, 3> radiance) {
        host.addCamera("/Camera", translation(0, 0, 5));
        addMaterial(host, "/Looks/Glow", {0, 0, 0}, 1.0f, 0.0f, radiance);
        addPlane(host, "/Plane", "/Looks/Glow");
        host.addRenderBuffer("/Buffers/display", "unorm8Vec4", kWidth, kHeight);
    }
    void setToken(const char* key, const std::string& token) { test::setToken(host, key, token); }
    std::array<float, 4> centre() {
        EXPECT_EQ(host.render("/Camera", {{"display", "/Buffers/display"}}), OBSCURA_OK) << host.lastError();
        ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
        EXPECT_EQ(host.api().mapRenderBuffer(host.delegate(), "/Buffers/display", &m), OBSCURA_OK);
        const auto* p = static_cast<const uint8_t*>(m.data) + (32 * kWidth + 32) * 4;
        std::array<float, 4> out{p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, p[3] / 255.0f};
        host.api().unmapRenderBuffer(host.delegate(), "/Buffers/display");
        return out;
    }
};

// 8-bit output rounding plus the LUT's measured interpolation error (color_lut_test).
void expectDisplay(const std::array<float, 4>& got, const std::array<float, 3>& want, float lutTolerance) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], lutTolerance + 0.5f / 255.0f) << "channel " << c;
    EXPECT_EQ(got[3], 1.0f);
}

TEST(ColorManagement, StandardViewIsTheSrgbEncoding) {
    // 0.1875 and 0.75 are exact in B10G11R11.
    EmissivePlane scene({0.1875f, 0.75f, 0.1875f});
    scene.setToken("ocio:view", "Standard");
    auto reference = std::get<std::array<float, 3>>(passes::applyViewTransform({"", "", "Standard", ""}, {0.1875f, 0.75f, 0.1875f}));
    auto got = scene.centre();
    EXPECT_NEAR(reference[0], 0.4706f, 0.002f) << "sRGB(0.1875)";
    expectDisplay(got, reference, 0.006f);
}

TEST(ColorManagement, DefaultFilmicViewMatchesOcio) {
    for (float v : {0.1875f, 0.75f, 3.0f}) {
        EmissivePlane scene({v, v * 0.5f, v * 0.25f});
        auto reference = std::get<std::array<float, 3>>(passes::applyViewTransform({}, {v, v * 0.5f, v * 0.25f}));
        for (auto& r : reference) r = std::clamp(r, 0.0f, 1.0f);
        expectDisplay(scene.centre(), reference, 0.02f);
    }
}

TEST(ColorManagement, UnknownViewIsRefusedWithTheValidNames) {
    EmissivePlane scene({0.5f, 0.5f, 0.5f});
    scene.setToken("ocio:view", "Cinematic");
    EXPECT_EQ(scene.host.render("/Camera", {{"display", "/Buffers/display"}}), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(scene.host.lastError().find("Filmic"), std::string::npos) << scene.host.lastError();
}

// ---- Grading from a chart (seed 004 "Color grading") ---------------------------------------

float gamma12(float v) { return std::pow(v, 1.2f); }

TEST(ColorGrading, NeutralChartRoundTripsToTheIdentity) {
    std::string path = writeGradedChart("neutral_chart", [](float v) { return v; }, 40);
    // Rendered through it, the display values do not move by more than one 8-bit step.
    for (const char* interpolation : {"trilinear", "tetrahedral"}) {
        EmissivePlane scene({0.1875f, 0.75f, 0.3f});
        scene.setToken("ocio:view", "Standard");
        auto plain = scene.centre();
        scene.setToken("grading:chart", path);
        scene.setToken("grading:interpolation", interpolation);
        auto graded = scene.centre();
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(graded[c], plain[c], 1.0f / 255.0f) << interpolation << " channel " << c;
    }
    std::filesystem::remove(path);
}

TEST(ColorGrading, AGammaAppliedToTheChartGradesTheDisplayValues) {
    std::string path = writeGradedChart("gamma_chart", gamma12);
    // End to end: the display value is the view's, then the grade. Tolerances: the 33^3 view LUT's
    // (expectDisplay's 0.006, steepened by the grade's slope, at most 1.2), the chart's 8-bit
    // rounding (half a step), the lattice's linear interpolation of x^1.2 over a 1/15 cell (under
    // 0.0011 above 0.3: h^2/8 max|f''|), and the output's rounding (expectDisplay).
    const std::array<float, 3> radiance{0.1875f, 0.75f, 0.3f};
    auto view = std::get<std::array<float, 3>>(passes::applyViewTransform({"", "", "Standard", ""}, radiance));
    EmissivePlane scene(radiance);
    scene.setToken("ocio:view", "Standard");
    scene.setToken("grading:chart", path);
    std::array<float, 3> want;
    for (int c = 0; c < 3; ++c) want[c] = gamma12(view[c]);
    expectDisplay(scene.centre(), want, 0.006f * 1.2f + 0.5f / 255.0f + 0.0011f);
    std::filesystem::remove(path);
}

TEST(ColorGrading, UnreadableOrSmallChartsAreRefusedWithTheReason) {
    EmissivePlane scene({0.5f, 0.5f, 0.5f});
    scene.setToken("grading:chart", "/nonexistent/graded.png");
    EXPECT_EQ(scene.host.render("/Camera", {{"display", "/Buffers/display"}}), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(scene.host.lastError().find("/nonexistent/graded.png"), std::string::npos) << scene.host.lastError();

    auto small = std::filesystem::temp_directory_path() / ("obscura_small_chart_" + std::to_string(getpid()) + ".png");
    ASSERT_FALSE(image::isError(image::writePng(small.string(), image::Image::make(64, 16, {"R", "G", "B"}))));
    scene.setToken("grading:chart", small.string());
    EXPECT_EQ(scene.host.render("/Camera", {{"display", "/Buffers/display"}}), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(scene.host.lastError().find("64x16"), std::string::npos) << scene.host.lastError();
    std::filesystem::remove(small);

    // Without a chart the frame renders again.
    scene.setToken("grading:chart", "");
    EXPECT_EQ(scene.host.render("/Camera", {{"display", "/Buffers/display"}}), OBSCURA_OK) << scene.host.lastError();

    const char* bad = "cubic";
    ObscuraValue v{OBSCURA_VALUE_TOKEN, 0, 1, &bad};
    EXPECT_EQ(scene.host.api().setRenderSetting(scene.host.delegate(), "grading:interpolation", &v),
              OBSCURA_ERROR_INVALID_ARGUMENT);
}

}  // namespace
}  // namespace obscura::test
