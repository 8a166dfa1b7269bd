// Soft shadows from a light's size (percentage-closer soft shadows, shaders/common/shadow_sampling.glsl)
// against physics: the penumbra of a straight edge under a distant light of angular diameter
// theta, and a Lambert sphere on a plane against the reference mode, which integrates each
// light's emitter point by point (delegate/prims/light.h emitterSample).
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <chrono>
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


// --- A Lambert sphere on a plane --------------------------------------------------------------

// A UV sphere (smooth vertex normals computed by the delegate) of `rings` x 2 rings segments.
void addSphere(TestHost& host, const std::string& path, std::array<double, 3> centre, double radius, int rings,
               const std::string& material) {
    std::vector<std::array<float, 3>> points;
    std::vector<int32_t> counts, indices;
    const int segments = 2 * rings;
    points.push_back({float(centre[0]), float(centre[1]), float(centre[2] + radius)});
    for (int r = 1; r < rings; ++r) {
        double theta = kPi * r / rings;
        for (int s = 0; s < segments; ++s) {
            double phi = 2.0 * kPi * s / segments;
            points.push_back({float(centre[0] + radius * std::sin(theta) * std::cos(phi)),
                              float(centre[1] + radius * std::sin(theta) * std::sin(phi)),
                              float(centre[2] + radius * std::cos(theta))});
        }
    }
    points.push_back({float(centre[0]), float(centre[1]), float(centre[2] - radius)});
    auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
    const int south = int(points.size()) - 1;
    for (int s = 0; s < segments; ++s) {
        counts.push_back(3);
        indices.insert(indices.end(), {0, ring(1, s), ring(1, s + 1)});
    }
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            counts.push_back(4);
            indices.insert(indices.end(), {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s + 1)});
        }
    for (int s = 0; s < segments; ++s) {
        counts.push_back(3);
        indices.insert(indices.end(), {ring(rings - 1, s), south, ring(rings - 1, s + 1)});
    }
    host.addPrim("mesh", path,
                 {{"points", HostValue::points(points)},
                  {"faceVertexCounts", HostValue::intArray(counts)},
                  {"faceVertexIndices", HostValue::intArray(indices)},
                  {"subdivisionScheme", HostValue::token("none")},
                  {"material:binding", HostValue::path(material)}});
}

// Half the width of a 640x360 still: at 96x54 every shadow-map texel was a fraction of a pixel, so
// the test could not see how wide the lookup's filter made the shadow's edges.
constexpr int kSphereWidth = 320, kSphereHeight = 180;

struct SphereScene {
    TestHost host;
    explicit SphereScene(double angleDegrees) {
        host.addCamera("/Camera", lookingAlongY({0.0, -5.0, 2.5}, 22.0), 35.0f, 36.0f);
        host.set("/Camera", "verticalAperture", HostValue::floatValue(36.0f * kSphereHeight / kSphereWidth));
        host.set("/Camera", "clippingRange", HostValue::float2(0.5f, 50.0f));
        addMaterial(host, "/Looks/Grey", {kLitPlaneAlbedo, kLitPlaneAlbedo, kLitPlaneAlbedo});
        addPlane(host, "/Ground", "/Looks/Grey", 6.0);
        addSphere(host, "/Ball", {0.0, 0.0, 1.0}, 1.0, 48, "/Looks/Grey");
        addSun(host, {0.6, 0.5, -1.0}, 3.0, angleDegrees);
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kSphereWidth, kSphereHeight);
    }
};

float reinhard(float x) { return x / (1.0f + x); }

image::Image mapped(const std::vector<float>& rgba) {
    image::Image img = rgbImage(rgba, kSphereWidth, kSphereHeight);
    for (float& v : img.pixels) v = reinhard(v);
    return img;
}

// The bar: default settings against the reference, 50 dB on x / (1 + x) of linear RGB.
void expectSphereMatchesReference(double angleDegrees) {
    SphereScene s(angleDegrees);
    auto start = std::chrono::steady_clock::now();
    // 256 sub-frames keep the test short; their first 128 (the sequences are nested) show how far
    // the reference has converged.
    image::Image reference = mapped(renderReference(s.host, 256));
    image::Image halfReference = mapped(renderReference(s.host, 128));
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    image::Image rendered = mapped(renderConverged(s.host));
    image::CompareMetrics m = compareImages(rendered, reference);
    image::CompareMetrics converged = compareImages(halfReference, reference);
    std::printf("[ metric ] sphere under a %.2f-degree sun, %dx%d: default vs reference 256: %.2f dB, SSIM %.5f, "
                "max error %.4f; reference 128 vs 256: %.2f dB (%.1f s for both references)\n",
                angleDegrees, kSphereWidth, kSphereHeight, m.psnr, m.ssim, m.maxAbsError, converged.psnr, seconds);
    // The reference has converged far beyond the bar it sets.
    EXPECT_GT(converged.psnr, 60.0);
    EXPECT_GE(m.psnr, 50.0);
}

TEST(SoftShadows, SphereUnderTheDefaultSunMatchesTheReference) { expectSphereMatchesReference(0.53); }

TEST(SoftShadows, SphereUnderAWideSunMatchesTheReference) { expectSphereMatchesReference(5.0); }

}  // namespace
}  // namespace obscura::test
