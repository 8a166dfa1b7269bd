// Soft shadows from a light's size (percentage-closer soft shadows, shaders/common/shadow_sampling.glsl)
// against physics: the penumbra of a straight edge under a distant light of angular diameter
// theta, and a Lambert sphere on a plane against the reference mode, which integrates each
// light's emitter point by point (delegate/prims/light.h emitterSample).
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace obscura::test {
namespace {

// Renders until temporal AA reports the still converged (a plain `obscura render`).
std::vector<float> renderConverged(TestHost& host) {
    std::vector<float> color;
    for (int renders = 0; renders < 100; ++renders) {
        EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
        color = host.readFloats("/Buffers/color");
        if (renderStats(host).converged) break;
    }
    EXPECT_TRUE(renderStats(host).converged);
    EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    return color;
}

std::vector<float> renderReference(TestHost& host, int subFrames) {
    setNumber(host, "reference", subFrames);
    EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    setNumber(host, "reference", 0);
    return host.readFloats("/Buffers/color");
}

// A distant light of irradiance `irradiance` (normalize on) travelling along `direction`, of
// angular diameter `angleDegrees` (UsdLux inputs:angle), diffuse only.
void addSun(TestHost& host, std::array<double, 3> direction, double irradiance, double angleDegrees) {
    host.addPrim("distantLight", "/Sun",
                 {{"inputs:intensity", HostValue::floatValue(float(irradiance))},
                  {"inputs:normalize", HostValue::boolean(true)},
                  {"inputs:angle", HostValue::floatValue(float(angleDegrees))},
                  {"inputs:specular", HostValue::floatValue(0.0f)}},
                  lightPointingAlong(direction));
}

// --- The straight edge ----------------------------------------------------------------------
// A disc light of angular radius a seen from a receiver beside a straight edge at distance d along
// the light (the light perpendicular to the receiver): the disc projects onto the receiver as a
// circle of radius R = d tan(a), and the light reaching a point at signed distance t R from the
// edge's shadow line is the share of that disc beyond a chord, F(t) = 1/2 + (t sqrt(1 - t^2) +
// asin t) / pi. The full (0-100%) penumbra is 2R = 2 d tan(theta / 2) ~ d tan(theta); its 10%-90%
// width, which a rendered profile measures without the noise of its tails, is 2 t90 R with F(t90) =
// 0.9 (t90 = 0.6870).
double chordShare(double t) { return 0.5 + (t * std::sqrt(1.0 - t * t) + std::asin(t)) / kPi; }

double chordShareInverse(double share) {
    double lo = -1.0, hi = 1.0;
    for (int i = 0; i < 60; ++i) (chordShare(0.5 * (lo + hi)) < share ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
}

struct EdgeCase {
    double angleDegrees;  // inputs:angle, the light's angular diameter
    double height;        // the occluder's edge above the receiver
};

// The 10%-90% width, in world units on the receiver, of the light's rise across the middle rows.
struct Profile {
    double width10To90 = -1.0;
    double expected = 0.0;
    double pixelWorld = 0.0;
};

// The receiver is the plane z = 0; the occluder a thin slab over x < 0 whose lower face, the one
// the receiver sees, is at z = height; the light travels straight down. The camera looks straight
// down from below the occluder, so it sees only the receiver; its view spans four full penumbrae.
Profile measureEdgePenumbra(const EdgeCase& c, int referenceSubFrames) {
    constexpr int kSize = 96;
    constexpr float kFocal = 20.0f, kAperture = 20.955f;
    const double tanHalfFov = (kAperture / 2.0) / kFocal;
    const double fullWidth = 2.0 * c.height * std::tan(c.angleDegrees * kPi / 360.0);
    const double cameraHeight = 4.0 * fullWidth / (2.0 * tanHalfFov);
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, cameraHeight), kFocal, kAperture);
    host.set("/Camera", "clippingRange", HostValue::float2(float(0.05 * cameraHeight), float(2.0 * cameraHeight)));
    addMaterial(host, "/Looks/Grey", {kLitPlaneAlbedo, kLitPlaneAlbedo, kLitPlaneAlbedo});
    addPlane(host, "/Receiver", "/Looks/Grey", 10.0);
    addBox(host, "/Occluder", {-10.0, -10.0, c.height}, {0.0, 10.0, c.height * 1.02}, "/Looks/Grey");
    const double irradiance = 3.0;
    addSun(host, {0.0, 0.0, -1.0}, irradiance, c.angleDegrees);
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kSize, kSize);
    setNumber(host, "ssao", 0);
    // 256-texel maps: the penumbra's filter stays within its widest radius (shadow_sampling.glsl).
    setNumber(host, "shadows:resolution", 256);
    std::vector<float> color = referenceSubFrames > 0 ? renderReference(host, referenceSubFrames) : renderConverged(host);

    const double lit = kLitPlaneAlbedo / kPi * irradiance;
    // The light's share along x, averaged over the middle half of the rows.
    std::vector<double> share(kSize, 0.0);
    for (int y = kSize / 4; y < 3 * kSize / 4; ++y)
        for (int x = 0; x < kSize; ++x) share[size_t(x)] += color[(size_t(y) * kSize + x) * 4] / lit / (kSize / 2);
    // The receiver's x under pixel centres, and the first rise through `level` between two of them.
    const double pixelWorld = 2.0 * cameraHeight * tanHalfFov / kSize;
    auto crossing = [&](double level) {
        for (int x = 0; x + 1 < kSize; ++x)
            if (share[size_t(x)] < level && share[size_t(x + 1)] >= level)
                return (x + 0.5 + (level - share[size_t(x)]) / (share[size_t(x + 1)] - share[size_t(x)])) * pixelWorld;
        return std::nan("");
    };
    Profile p;
    p.width10To90 = crossing(0.9) - crossing(0.1);
    p.expected = chordShareInverse(0.9) * fullWidth;
    p.pixelWorld = pixelWorld;
    EXPECT_NEAR(share[0], 0.0, 0.01) << "the umbra at the image's left edge";
    EXPECT_NEAR(share[kSize - 1], 1.0, 0.02) << "the lit receiver at the image's right edge";
    return p;
}

const EdgeCase kEdgeCases[] = {{2.0, 1.0}, {2.0, 2.0}, {8.0, 1.0}, {8.0, 2.0}};

// Tolerance: 5% of the width plus one pixel of the camera. The crossings are interpolated between
// pixel centres and the camera's jittered pixel footprint widens the ramp; the 3x3-texel minimum
// filter and the sampling of the disc (16 taps over 16 frames, or 256 sub-frames) widen or
// roughen it by a few per cent of a ramp 16 to 24 pixels wide.
void expectPenumbra(const char* mode, const EdgeCase& c, const Profile& p) {
    double tolerance = 0.05 * p.expected + p.pixelWorld;
    std::printf("[ metric ] %s: angle %.1f deg, edge %.1f above: 10-90%% width %.5f, expected %.5f (d tan theta "
                "%.5f full), error %+.1f%% (tolerance %.1f%%)\n",
                mode, c.angleDegrees, c.height, p.width10To90, p.expected,
                c.height * std::tan(c.angleDegrees * kPi / 180.0), 100.0 * (p.width10To90 / p.expected - 1.0),
                100.0 * tolerance / p.expected);
    EXPECT_NEAR(p.width10To90, p.expected, tolerance) << mode << " angle " << c.angleDegrees << " height " << c.height;
}

TEST(SoftShadows, StraightEdgePenumbraIsHeightTimesTheLightsAngle) {
    for (const EdgeCase& c : kEdgeCases) expectPenumbra("soft shadows", c, measureEdgePenumbra(c, 0));
}

TEST(SoftShadows, ReferenceIntegratesTheDistantLightsDisc) {
    // The ground truth itself: 256 hard shadows from directions spread over the light's cone.
    for (const EdgeCase& c : {kEdgeCases[0], kEdgeCases[3]})
        expectPenumbra("reference (256)", c, measureEdgePenumbra(c, 256));
}

}  // namespace
}  // namespace obscura::test
