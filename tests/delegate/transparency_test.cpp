// Transparent surfaces (opacity below 1, no opacityThreshold): drawn after lighting by the forward
// pass, back to front, blended "over" with premultiplied colour. Planes face the camera (at
// (0, 0, 5) looking down -Z) under a distant light 30 degrees off the normal with no specular, so
// each surface's lit radiance is Lambert's albedo / pi * E * cos, and a pixel's radiance is the
// analytic "over" of the surfaces in front of each other: c = a c_front + (1 - a) c_behind.
// The light crosses the transparent planes before reaching the opaque one: transparent surfaces
// cast no shadow, so the opaque plane is fully lit in every expectation.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace obscura::test {
namespace {

constexpr double kIrradiance = 3.0;
constexpr double kTilt = 30.0 * kPi / 180.0;
const double kLambert = kIrradiance * std::cos(kTilt) / kPi;  // radiance per unit albedo

using Rgb = std::array<double, 3>;

Rgb lit(std::array<float, 3> albedo) { return {albedo[0] * kLambert, albedo[1] * kLambert, albedo[2] * kLambert}; }
Rgb over(double alpha, Rgb front, Rgb behind) {
    Rgb c{};
    for (size_t i = 0; i < 3; ++i) c[i] = alpha * front[i] + (1.0 - alpha) * behind[i];
    return c;
}

// The colour of a partly covered pixel (its alpha is checked apart), with expectRadiance's tolerance.
void expectPremultipliedRadiance(const std::vector<float>& color, int x, int y, Rgb expected) {
    const float* p = &color[(size_t(y) * kWidth + size_t(x)) * 4];
    const int mantissa[3] = {6, 6, 5};
    for (int c = 0; c < 3; ++c) {
        double e = expected[size_t(c)];
        EXPECT_NEAR(p[c], e, 0.01 * e + smallFloatStep(float(e), mantissa[c]))
            << "pixel (" << x << ", " << y << ") channel " << c;
    }
}

struct TransparencyScene {
    TestHost host;
    std::vector<float> color;
    std::vector<int32_t> primIds;
    TransparencyScene() {
        host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength, kLitPlaneAperture);
        host.addPrim("distantLight", "/Sun",
                     {{"inputs:intensity", HostValue::floatValue(float(kIrradiance))},
                      {"inputs:normalize", HostValue::boolean(true)},
                      {"inputs:specular", HostValue::floatValue(0.0f)}},
                     lightPointingAlong({std::sin(kTilt), 0.0, -std::cos(kTilt)}));
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/primId", "int32", kWidth, kHeight);
    }
    void addSurface(const std::string& path, std::array<float, 3> albedo, float opacity, double z, double half) {
        addMaterial(host, path + "Look", albedo);
        host.set(path + "Look", "inputs:opacity", HostValue::floatValue(opacity));
        addPlane(host, path, path + "Look", half, translation(0, 0, z));
    }
    void setting(const char* name, double value) {
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &value};
        ASSERT_EQ(host.api().setRenderSetting(host.delegate(), name, &v), OBSCURA_OK) << name;
    }
    void render() {
        ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}, {"primId", "/Buffers/primId"}}), OBSCURA_OK)
            << host.lastError();
        ASSERT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
        color = host.readFloats("/Buffers/color");
        primIds = host.readInts("/Buffers/primId");
    }
    const float* at(int x, int y) const { return &color[(size_t(y) * kWidth + size_t(x)) * 4]; }
    int32_t primIdAt(int x, int y) const { return primIds[size_t(y) * kWidth + size_t(x)]; }
    int32_t primIdOf(const std::string& path) {
        int32_t id = -1;
        EXPECT_EQ(host.api().getPrimId(host.delegate(), path.c_str(), &id), OBSCURA_OK);
        return id;
    }
    void print(const char* what, Rgb expected) const {
        const float* p = at(32, 32);
        std::printf("[ metric ] %s: pixel (%.4f, %.4f, %.4f, a %.4f), analytic (%.4f, %.4f, %.4f)\n", what,
                    double(p[0]), double(p[1]), double(p[2]), double(p[3]), expected[0], expected[1], expected[2]);
    }
};

const std::array<float, 3> kWhite = {kLitPlaneAlbedo, kLitPlaneAlbedo, kLitPlaneAlbedo};  // 8-bit sRGB exact
const std::array<float, 3> kRed = {0.9f, 0.1f, 0.05f};
const std::array<float, 3> kBlue = {0.05f, 0.2f, 0.8f};

TEST(Transparency, HalfOpaqueRedOverLitWhiteIsTheAnalyticBlend) {
    TransparencyScene s;
    s.addSurface("/Floor", kWhite, 1.0f, 0.0, 10.0);
    s.addSurface("/Pane", kRed, 0.5f, 1.0, 10.0);
    s.render();
    Rgb expected = over(0.5, lit(kRed), lit(kWhite));
    s.print("red 0.5 over white", expected);
    for (auto [x, y] : {std::pair{32, 32}, {5, 7}, {60, 50}}) expectRadiance(s.color, x, y, expected);
    EXPECT_NEAR(s.at(32, 32)[3], 1.0f, 1e-3f) << "over an opaque surface the pixel is covered";
    // Transparent surfaces write no G-buffer: ids, depth and normals are the opaque surface's.
    EXPECT_EQ(s.primIdAt(32, 32), s.primIdOf("/Floor"));
    // Pre-exposed like the lighting pass: one stop more doubles the blend.
    s.setting("exposure", 1.0);
    s.render();
    Rgb brighter = {2.0 * expected[0], 2.0 * expected[1], 2.0 * expected[2]};
    s.print("red 0.5 over white, exposure +1", brighter);
    expectRadiance(s.color, 32, 32, brighter);
}

TEST(Transparency, OverlappingPanesSortBackToFrontInEitherSubmissionOrder) {
    // Submission order is path order (/A before /B); each arrangement puts the other one in front.
    for (bool aInFront : {true, false}) {
        TransparencyScene s;
        s.addSurface("/Floor", kWhite, 1.0f, 0.0, 10.0);
        s.addSurface("/A", kRed, 0.5f, aInFront ? 2.0 : 1.0, 9.0);
        s.addSurface("/B", kBlue, 0.5f, aInFront ? 1.0 : 2.0, 10.0);
        s.render();
        Rgb behindFront = over(0.5, lit(aInFront ? kBlue : kRed), lit(kWhite));
        Rgb expected = over(0.5, lit(aInFront ? kRed : kBlue), behindFront);
        s.print(aInFront ? "red over blue over white" : "blue over red over white", expected);
        for (auto [x, y] : {std::pair{32, 32}, {20, 40}}) expectRadiance(s.color, x, y, expected);
    }
}

TEST(Transparency, PaneBehindAnOpaqueSurfaceIsHidden) {
    TransparencyScene s;
    s.addSurface("/Pane", kRed, 0.5f, 0.0, 10.0);
    s.addSurface("/Wall", kWhite, 1.0f, 1.0, 10.0);
    s.render();
    s.print("red behind white", lit(kWhite));
    for (auto [x, y] : {std::pair{32, 32}, {5, 7}}) expectRadiance(s.color, x, y, lit(kWhite));
}

TEST(Transparency, OpaqueMaterialsStayDeferred) {
    // opacity 1 (authored) renders exactly as the default material does, through the G-buffer.
    TransparencyScene authored, fallback;
    authored.addSurface("/Floor", kWhite, 1.0f, 0.0, 10.0);
    addMaterial(fallback.host, "/FloorLook", kWhite);
    addPlane(fallback.host, "/Floor", "/FloorLook", 10.0);
    authored.render();
    fallback.render();
    ASSERT_EQ(authored.color.size(), fallback.color.size());
    size_t differing = 0;
    for (size_t i = 0; i < authored.color.size(); ++i) differing += authored.color[i] != fallback.color[i];
    std::printf("[ metric ] opacity 1 against no opacity: %zu differing channel values\n", differing);
    EXPECT_EQ(differing, 0u);
    EXPECT_EQ(authored.primIdAt(32, 32), authored.primIdOf("/Floor")) << "an opaque surface is in the G-buffer";
    expectRadiance(authored.color, 32, 32, lit(kWhite));
}

// The colour AOV is premultiplied RGBA (DESIGN.md): over the empty background a pane of opacity a
// gives alpha a and colour a x its lit radiance; two panes give 1 - (1 - a1)(1 - a2), the "over"
// of their coverages. Through temporal AA (the default) and without it (the G-buffer's coverage).
TEST(Transparency, ColorAovAlphaIsThePremultipliedCoverage) {
    for (double taa : {1.0, 0.0}) {
        TransparencyScene s;
        s.setting("taa", taa);
        s.addSurface("/A", kRed, 0.5f, 1.0, 10.0);
        s.addSurface("/B", kBlue, 0.25f, 0.0, 0.5);  // the view spans +-1.05 at z = 0: a centre patch
        s.render();
        Rgb one = over(0.5, lit(kRed), {0, 0, 0});
        Rgb two = over(0.5, lit(kRed), over(0.25, lit(kBlue), {0, 0, 0}));
        s.print(taa != 0.0 ? "panes over the background (taa)" : "panes over the background (no taa)", two);
        expectPremultipliedRadiance(s.color, 32, 32, two);
        EXPECT_NEAR(s.at(32, 32)[3], 1.0 - 0.5 * 0.75, 2.0 / 255.0) << "both panes, taa " << taa;
        // Pixel (1, 1) lies outside the small pane: only /A covers it.
        expectPremultipliedRadiance(s.color, 1, 1, one);
        EXPECT_NEAR(s.at(1, 1)[3], 0.5, 2.0 / 255.0) << "one pane, taa " << taa;
        EXPECT_EQ(s.primIdAt(32, 32), -1) << "nothing opaque drew";
    }
}

TEST(Transparency, FadeDistanceSoftensTheIntersection) {
    // transparents:fadeDistance (metres; metersPerUnit 1): a pane 0.5 in front of the floor with a
    // fade distance of 2 keeps a quarter of its coverage.
    TransparencyScene s;
    s.setting("metersPerUnit", 1.0);
    s.setting("transparents:fadeDistance", 2.0);
    s.addSurface("/Floor", kWhite, 1.0f, 0.0, 10.0);
    s.addSurface("/Pane", kRed, 0.8f, 0.5, 10.0);
    s.render();
    Rgb expected = over(0.8 * 0.25, lit(kRed), lit(kWhite));
    s.print("faded pane over white", expected);
    expectRadiance(s.color, 32, 32, expected);
}

TEST(Transparency, ClearGlassKeepsItsReflection) {
    // UsdPreviewSurface: "perfectly clear glass still has a specular response". A black pane of
    // opacity 0 under a white dome of radiance 1 reflects the split-sum response F0 A + B (ior 1.5:
    // F0 = 0.04) with alpha 0: added light over the background, premultiplied. With the dome hidden
    // from the camera (domeLightCameraVisibility off) the background is empty; seen, the sky is
    // the opaque background and the pane adds its reflection over it.
    TestHost host;
    int32_t off = 0;
    ObscuraValue hidden{OBSCURA_VALUE_BOOL, 0, 1, &off};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "domeLightCameraVisibility", &hidden), OBSCURA_OK);
    host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength, kLitPlaneAperture);
    host.addPrim("domeLight", "/Sky", {{"inputs:intensity", HostValue::floatValue(1.0f)}});
    addMaterial(host, "/GlassLook", {0, 0, 0}, 0.5f);
    host.set("/GlassLook", "inputs:opacity", HostValue::floatValue(0.0f));
    addPlane(host, "/Glass", "/GlassLook", 10.0, translation(0, 0, 1));
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
    ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    auto color = host.readFloats("/Buffers/color");
    auto [a, b] = environmentBrdf(0.5, 1.0);  // the centre pixel looks straight at the pane
    double expected = 0.04 * a + b;
    std::printf("[ metric ] clear glass reflection: %.4f, split sum %.4f, alpha %.4f\n",
                double(color[(32 * kWidth + 32) * 4]), expected, double(color[(32 * kWidth + 32) * 4 + 3]));
    expectPremultipliedRadiance(color, 32, 32, {expected, expected, expected});
    EXPECT_NEAR(color[(32 * kWidth + 32) * 4 + 3], 0.0f, 1e-6f);

    int32_t on = 1;
    ObscuraValue seen{OBSCURA_VALUE_BOOL, 0, 1, &on};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "domeLightCameraVisibility", &seen), OBSCURA_OK);
    ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    color = host.readFloats("/Buffers/color");
    expectPremultipliedRadiance(color, 32, 32, {1.0 + expected, 1.0 + expected, 1.0 + expected});
    EXPECT_NEAR(color[(32 * kWidth + 32) * 4 + 3], 1.0f, 1e-6f);
}

}  // namespace
}  // namespace obscura::test
