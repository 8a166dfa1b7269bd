// UsdPreviewSurface `occlusion`: it darkens the ambient (dome) light only, as the spec has it
// ("used to darken indirect lighting"), and direct light stays whole. The G-buffer carries it in
// 8 bits (the instance target's top byte), so expectations allow one step of 1/255 on top of the
// analytic tolerance of expectRadiance.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace obscura::test {
namespace {

constexpr double kSkyRadiance = 1.5;
constexpr double kSunIrradiance = 2.0;
constexpr double kSunTilt = 30.0 * kPi / 180.0;

// The lit plane under a constant dome and a distant light, both without specular, SSAO off so
// the dome's share is exactly albedo x L (Lambert under a uniform environment).
struct OccludedPlane {
    LitPlaneScene s;
    explicit OccludedPlane(bool withSun) {
        s.host.addPrim("domeLight", "/Sky",
                       {{"inputs:intensity", HostValue::floatValue(float(kSkyRadiance))},
                        {"inputs:specular", HostValue::floatValue(0.0f)}});
        if (withSun)
            s.host.addPrim("distantLight", "/Sun",
                           {{"inputs:intensity", HostValue::floatValue(float(kSunIrradiance))},
                            {"inputs:normalize", HostValue::boolean(true)},
                            {"inputs:specular", HostValue::floatValue(0.0f)}},
                           lightPointingAlong({std::sin(kSunTilt), 0.0, -std::cos(kSunTilt)}));
        double off = 0.0;
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &off};
        EXPECT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "ssao", &v), OBSCURA_OK);
    }
    std::vector<float> renderWithOcclusion(float occlusion) {
        s.host.set("/Looks/Grey", "inputs:occlusion", HostValue::floatValue(occlusion));
        EXPECT_EQ(s.host.api().markDirty(s.host.delegate(), "/Looks/Grey", OBSCURA_DIRTY_PARAMS), OBSCURA_OK);
        return s.renderColor();
    }
};

TEST(MaterialOcclusion, ScalesTheDomeAndNotTheSun) {
    OccludedPlane scene(true);
    const double ambient = kLitPlaneAlbedo * kSkyRadiance;
    const double direct = kLitPlaneAlbedo / kPi * kSunIrradiance * std::cos(kSunTilt);
    for (float occlusion : {1.0f, 0.25f, 0.0f}) {
        auto color = scene.renderWithOcclusion(occlusion);
        double expected = occlusion * ambient + direct;
        const float* p = &color[(32 * kWidth + 32) * 4];
        std::printf("[ metric ] occlusion %.2f: radiance %.4f, analytic %.4f (ambient %.4f + direct %.4f)\n",
                    double(occlusion), double(p[0]), expected, occlusion * ambient, direct);
        for (auto [x, y] : {std::pair{32, 32}, {5, 7}, {60, 50}})
            expectRadiance(color, x, y, {expected, expected, expected});
    }
}

TEST(MaterialOcclusion, QuarterOcclusionQuartersTheAmbientLight) {
    OccludedPlane scene(false);
    auto open = scene.renderWithOcclusion(1.0f);
    auto occluded = scene.renderWithOcclusion(0.25f);
    const float* a = &open[(32 * kWidth + 32) * 4];
    const float* b = &occluded[(32 * kWidth + 32) * 4];
    std::printf("[ metric ] ambient with occlusion 0.25 / with 1: %.4f (analytic 0.25)\n", double(b[0] / a[0]));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(b[c] / a[c], 0.25, 0.01 + 1.0 / 255.0 + 2.0 * smallFloatStep(1.0f, c == 2 ? 5 : 6))
            << "channel " << c;
}

// Bad values are reported like other bad material inputs: the material is skipped (its meshes
// fall back to the default material) and the render says why.
TEST(MaterialOcclusion, BadValuesAreReported) {
    for (HostValue bad : {HostValue::floatValue(-0.5f), HostValue::floatValue(1.5f), HostValue::token("dark")}) {
        LitPlaneScene s;
        s.host.expectError("skipped prim /Looks/Grey: inputs:occlusion");
        s.host.set("/Looks/Grey", "inputs:occlusion", bad);
        EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
        EXPECT_NE(s.host.lastError().find("/Looks/Grey"), std::string::npos) << s.host.lastError();
        ASSERT_FALSE(s.host.loggedErrors().empty());
        EXPECT_NE(s.host.loggedErrors().back().find("inputs:occlusion"), std::string::npos)
            << s.host.loggedErrors().back();
    }
}

}  // namespace
}  // namespace obscura::test
