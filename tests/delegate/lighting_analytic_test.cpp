// Analytic lighting: a Lambert plane's radiance under a distant and a sphere light equals what
// the BRDF predicts (albedo / pi * irradiance * cos) within 1%, plus one step of the
// B10G11R11 accumulation format (1.6% for R and G, 3.1% for B). The albedo is a value 8-bit
// sRGB holds exactly, so the G-buffer adds no error of its own.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

TEST(LightingAnalytic, LambertPlaneUnderDistantLight) {
    LitPlaneScene s;
    const double irradiance = 3.0;  // normalized distant light: intensity is the illuminance
    const double theta = 30.0 * kPi / 180.0;
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(float(irradiance))},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   lightPointingAlong({std::sin(theta), 0.0, -std::cos(theta)}));
    auto color = s.renderColor();
    double radiance = kLitPlaneAlbedo / kPi * irradiance * std::cos(theta);
    for (auto [x, y] : {std::pair{32, 32}, {5, 7}, {60, 50}}) expectRadiance(color, x, y, {radiance, radiance, radiance});
}

TEST(LightingAnalytic, DistantLightSolidAngleWhenNotNormalized) {
    LitPlaneScene s;
    // UsdLux: without normalize the intensity is radiance over the sun's disc.
    const double angle = 2.0 * kPi / 180.0, intensity = 5000.0;
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(float(intensity))},
                    {"inputs:angle", HostValue::floatValue(2.0f)},
                    {"inputs:color", HostValue::float3(1.0f, 0.5f, 0.25f)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   lightPointingAlong({0, 0, -1}));
    auto color = s.renderColor();
    double irradiance = intensity * 2.0 * kPi * (1.0 - std::cos(angle / 2.0));
    double r = kLitPlaneAlbedo / kPi * irradiance;
    expectRadiance(color, 32, 32, {r, r * 0.5, r * 0.25});
}

TEST(LightingAnalytic, LambertPlaneUnderSphereLight) {
    LitPlaneScene s;
    const double height = 2.0, radius = 0.1, radiance = 400.0;
    s.host.addPrim("sphereLight", "/Bulb",
                   {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                    {"inputs:radius", HostValue::floatValue(float(radius))},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   translation(0, 0, height));
    auto color = s.renderColor();
    // A sphere fully above the horizon: E = pi L (r/d)^2 cos(theta).
    for (auto [x, y] : {std::pair{32, 32}, {10, 20}, {50, 60}}) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double d2 = p[0] * p[0] + p[1] * p[1] + height * height;
        double cosTheta = height / std::sqrt(d2);
        double e = kPi * radiance * radius * radius / d2 * cosTheta;
        double l = kLitPlaneAlbedo / kPi * e;
        expectRadiance(color, x, y, {l, l, l});
    }
}

TEST(LightingAnalytic, EmissionAddsToReflectedLight) {
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength, kLitPlaneAperture);
    addMaterial(host, "/Looks/Glow", {0.5f, 0.5f, 0.5f}, 1.0f, 0.0f, {0.25f, 0.5f, 1.0f});
    addPlane(host, "/Plane", "/Looks/Glow");
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
    ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    auto color = host.readFloats("/Buffers/color");
    expectRadiance(color, 32, 32, {0.25, 0.5, 1.0});
}

TEST(LightingAnalytic, ExposureScalesTheColorAov) {
    LitPlaneScene s;
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(1.0f)},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   lightPointingAlong({0, 0, -1}));
    double stops = 2.0;
    ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &stops};
    ASSERT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "exposure", &v), OBSCURA_OK);
    auto color = s.renderColor();
    double r = kLitPlaneAlbedo / kPi * 4.0;
    expectRadiance(color, 32, 32, {r, r, r});
}

TEST(LightingAnalytic, PhysicalCameraExposureScalesTheColorAov) {
    // UsdGeomCamera: time x ISO x 2^exposure x responsivity / (100 x fStop^2) = 0.25 x 400 x 2 x 1.5
    // / (100 x 0.5^2) = 12, times 2^-1 from the render setting.
    LitPlaneScene s;
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(0.25f)},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   lightPointingAlong({0, 0, -1}));
    s.host.set("/Camera", "exposure:time", HostValue::floatValue(0.25f));
    s.host.set("/Camera", "exposure:iso", HostValue::floatValue(400.0f));
    s.host.set("/Camera", "exposure:fStop", HostValue::floatValue(0.5f));
    s.host.set("/Camera", "exposure:responsivity", HostValue::floatValue(1.5f));
    s.host.set("/Camera", "exposure", HostValue::floatValue(1.0f));
    double stops = -1.0;
    ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &stops};
    ASSERT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "exposure", &v), OBSCURA_OK);
    auto color = s.renderColor();
    double r = kLitPlaneAlbedo / kPi * 0.25 * 12.0 * 0.5;
    expectRadiance(color, 32, 32, {r, r, r});
}

}  // namespace
}  // namespace obscura::test

namespace obscura::test {
namespace {

TEST(LightingAnalytic, ConstantDomeGivesAlbedoTimesRadiance) {
    LitPlaneScene s;
    // Lambert under a uniform environment of radiance L: integral of (a/pi) L cos = a L.
    const double radiance = 1.5;
    s.host.addPrim("domeLight", "/Sky",
                   {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                    {"inputs:color", HostValue::float3(1.0f, 0.5f, 0.25f)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}});
    auto color = s.renderColor();
    double l = kLitPlaneAlbedo * radiance;
    for (auto [x, y] : {std::pair{32, 32}, {3, 60}}) expectRadiance(color, x, y, {l, l * 0.5, l * 0.25});
}

// A black-diffuse plane under a white dome of radiance 1: what reaches the eye is specular only.
struct SpecularUnderDome {
    LitPlaneScene s;
    SpecularUnderDome() {
        s.host.addPrim("domeLight", "/Sky", {{"inputs:intensity", HostValue::floatValue(1.0f)}});
        addMaterial(s.host, "/Looks/Coated", {0, 0, 0}, 0.5f);
        s.host.set("/Plane", "material:binding", HostValue::path("/Looks/Coated"));
        double off = 0.0;
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &off};
        EXPECT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "ssao", &v), OBSCURA_OK);
    }
    // N.V at a pixel of the plane seen from the camera.
    static double nDotV(int x, int y) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        return kLitPlaneCameraDistance / std::sqrt(p[0] * p[0] + p[1] * p[1] + 25.0);
    }
};

double schlick(double f0, double cosine) { return f0 + (1 - f0) * std::pow(1 - cosine, 5); }

TEST(Materials, SpecularWorkflowReflectsSpecularColor) {
    SpecularUnderDome d;
    d.s.host.set("/Looks/Coated", "inputs:useSpecularWorkflow", HostValue::intValue(1));
    d.s.host.set("/Looks/Coated", "inputs:specularColor", HostValue::float3(0.5f, 0.25f, 0.0f));
    d.s.host.set("/Looks/Coated", "inputs:metallic", HostValue::floatValue(1.0f));  // ignored by this workflow
    auto color = d.s.renderColor();
    for (auto [x, y] : {std::pair{32, 32}, {5, 50}}) {
        auto [a, b] = environmentBrdf(0.5, SpecularUnderDome::nDotV(x, y));
        expectRadiance(color, x, y, {0.5 * a + b, 0.25 * a + b, b});
    }
}

TEST(Materials, IorSetsTheDielectricReflectance) {
    SpecularUnderDome d;
    d.s.host.set("/Looks/Coated", "inputs:ior", HostValue::floatValue(2.5f));
    auto color = d.s.renderColor();
    const double f0 = std::pow((2.5 - 1) / (2.5 + 1), 2);
    auto [a, b] = environmentBrdf(0.5, SpecularUnderDome::nDotV(32, 32));
    expectRadiance(color, 32, 32, {f0 * a + b, f0 * a + b, f0 * a + b});
}

TEST(Materials, ClearcoatAddsAWhiteLobeAndDimsTheBase) {
    SpecularUnderDome d;
    d.s.host.set("/Looks/Coated", "inputs:diffuseColor", HostValue::float3(0.5f, 0.0f, 0.0f));
    d.s.host.set("/Looks/Coated", "inputs:clearcoat", HostValue::floatValue(1.0f));
    d.s.host.set("/Looks/Coated", "inputs:clearcoatRoughness", HostValue::floatValue(0.2f));
    auto color = d.s.renderColor();
    double nv = SpecularUnderDome::nDotV(32, 32);
    auto [a, b] = environmentBrdf(0.5, nv);
    auto [ca, cb] = environmentBrdf(0.2, nv);
    double transmission = 1 - schlick(0.04, nv);
    double coat = 0.04 * ca + cb, base = (0.04 * a + b) * transmission;
    const float* p = &color[(32 * kWidth + 32) * 4];
    // Green and blue see only the lobes; red adds the coat-dimmed diffuse (albedo stored as 8-bit sRGB).
    expectRadiance(color, 32, 32, {p[0], base + coat, base + coat});
    double albedo8 = srgb8Exact(int(std::lround(255.0 * (1.055 * std::pow(0.5, 1 / 2.4) - 0.055))));
    EXPECT_NEAR(p[0], albedo8 * transmission + base + coat, 0.01 * p[0] + smallFloatStep(p[0], 6));
}

TEST(LightingAnalytic, ColorTemperatureTintsTheLight) {
    LitPlaneScene s;
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(3.0f)},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:enableColorTemperature", HostValue::boolean(true)},
                    {"inputs:colorTemperature", HostValue::floatValue(3000.0f)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   lightPointingAlong({0, 0, -1}));
    auto color = s.renderColor();
    const float* p = &color[(32 * kWidth + 32) * 4];
    // The Planckian locus at 3000 K has CIE 1931 chromaticity (0.4369, 0.4041) (published tables);
    // its linear Rec.709 colour at luminance 1 is what the light's colour is multiplied by.
    const double x = 0.4369, y = 0.4041, X = x / y, Z = (1 - x - y) / y;
    double rgb[3] = {3.2404542 * X - 1.5371385 - 0.4985314 * Z, -0.9692660 * X + 1.8760108 + 0.0415560 * Z,
                     0.0556434 * X - 0.2040259 + 1.0572252 * Z};
    double luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    double e = kLitPlaneAlbedo / kPi * 3.0;
    const int mantissa[3] = {6, 6, 5};
    for (int c = 0; c < 3; ++c) {
        double want = e * rgb[c] / luminance;
        EXPECT_NEAR(p[c], want, 0.01 * want + smallFloatStep(float(want), mantissa[c])) << "channel " << c;
    }
    EXPECT_NEAR(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2], e, 0.03 * e) << "luminance is kept";
}

}  // namespace
}  // namespace obscura::test
