// Shadow maps against geometry: every ground pixel is classified on the CPU by casting its ray to
// the ground and from there towards the light through the occluding boxes. Pixels whose whole
// neighbourhood (kMarginPixels on each side) is shadowed must receive none of the light, pixels
// whose neighbourhood is lit must match the analytic Lambert radiance (lighting_analytic_test.cpp's
// tolerance: 1% plus one step of the accumulation format) — that also finds acne, which darkens
// lit pixels. The shadow's edge must lie where the occluder's edge projects along the light.
#include "harness/image/png_io.h"
#include "harness/usd_scene_host.h"
#include "tests/delegate/camera_scene.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <optional>

namespace obscura::test {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 add(Vec3 a, Vec3 b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 scale(Vec3 a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
Vec3 normalize(Vec3 a) { return scale(a, 1.0 / std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])); }

constexpr int kMarginPixels = 2;
const float kAlbedo = srgb8Exact(188);  // 0.5029

struct Box {
    Vec3 min, max;
};

// Does the segment from `origin` along `direction` (t in (0, tMax)) pass through the box? Slabs.
bool segmentHitsBox(Vec3 origin, Vec3 direction, double tMax, const Box& box) {
    double t0 = 1e-9, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(direction[a]) < 1e-15) {
            if (origin[a] < box.min[a] || origin[a] > box.max[a]) return false;
            continue;
        }
        double ta = (box.min[a] - origin[a]) / direction[a], tb = (box.max[a] - origin[a]) / direction[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1;
}

// A pinhole camera as the delegate builds it (Camera::projectionMatrix, "fit" conform; TestHost
// gives both apertures the same value), for casting each pixel's ray.
struct PinholeCamera {
    Matrix cameraToWorld;
    double focalLength, aperture;
    int width, height;

    Vec3 position() const { return {cameraToWorld[12], cameraToWorld[13], cameraToWorld[14]}; }
    // World direction through the image point (x, y) in pixels (pixel centres at +0.5).
    Vec3 ray(double x, double y) const {
        double ha = aperture, va = aperture, aspect = double(width) / height;
        if (aspect > ha / va) ha = va * aspect;
        else va = ha / aspect;
        double vx = (x / width * 2.0 - 1.0) * (ha / 2.0) / focalLength;
        double vy = (1.0 - y / height * 2.0) * (va / 2.0) / focalLength;
        const Matrix& m = cameraToWorld;
        return {vx * m[0] + vy * m[4] - m[8], vx * m[1] + vy * m[5] - m[9], vx * m[2] + vy * m[6] - m[10]};
    }
    // Where that ray meets the ground plane z = 0, if it does in front of the camera.
    std::optional<Vec3> ground(double x, double y) const {
        Vec3 d = ray(x, y), o = position();
        if (d[2] >= 0.0) return std::nullopt;
        return add(o, scale(d, -o[2] / d[2]));
    }
};

// The light as seen from a ground point: its direction (towards the light), the distance to it
// (infinite for a distant light) and the irradiance it delivers there.
struct LightAtPoint {
    Vec3 toLight;
    double distance;
    double irradiance;  // on the ground (cosine included)
};

struct ShadowScene {
    TestHost host;
    PinholeCamera camera;
    std::vector<Box> occluders;
    std::function<LightAtPoint(Vec3)> light;
    int32_t groundId = -1;

    ShadowScene(PinholeCamera cam, double groundHalfX, double groundY0, double groundY1) : camera(cam) {
        host.addCamera("/Camera", cam.cameraToWorld, float(cam.focalLength), float(cam.aperture));
        addMaterial(host, "/Looks/Grey", {kAlbedo, kAlbedo, kAlbedo});
        float hx = float(groundHalfX), y0 = float(groundY0), y1 = float(groundY1);
        host.addPrim("mesh", "/Ground",
                     {{"points", HostValue::points({{-hx, y0, 0}, {hx, y0, 0}, {hx, y1, 0}, {-hx, y1, 0}})},
                      {"faceVertexCounts", HostValue::intArray({4})},
                      {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                      {"subdivisionScheme", HostValue::token("none")},
                      {"material:binding", HostValue::path("/Looks/Grey")}});
        host.addRenderBuffer("/Buffers/color", "float32Vec4", cam.width, cam.height);
        host.addRenderBuffer("/Buffers/id", "int32", cam.width, cam.height);
    }
    void addOccluder(const std::string& path, Box box) {
        occluders.push_back(box);
        addBox(host, path, box.min, box.max, "/Looks/Grey");
    }
    void addDistantLight(Vec3 travel, double irradiance, std::map<std::string, HostValue> extra = {}) {
        Vec3 d = normalize(travel);
        std::map<std::string, HostValue> values = {{"inputs:intensity", HostValue::floatValue(float(irradiance))},
                                                   {"inputs:normalize", HostValue::boolean(true)},
                                                   {"inputs:angle", HostValue::floatValue(0.0f)},
                                                   {"inputs:specular", HostValue::floatValue(0.0f)}};
        values.insert(extra.begin(), extra.end());
        host.addPrim("distantLight", "/Sun", values, lightPointingAlong(d));
        light = [d, irradiance](Vec3) {
            return LightAtPoint{scale(d, -1.0), 1e30, irradiance * -d[2]};
        };
    }
    // A sphere light; `extra` may shape it into a spot (its cone must hold every point checked).
    void addSphereLight(Vec3 position, double radius, double radiance, std::map<std::string, HostValue> extra = {}) {
        std::map<std::string, HostValue> values = {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                                                   {"inputs:radius", HostValue::floatValue(float(radius))},
                                                   {"inputs:specular", HostValue::floatValue(0.0f)}};
        values.insert(extra.begin(), extra.end());
        host.addPrim("sphereLight", "/Bulb", values, translation(position[0], position[1], position[2]));
        light = [position, radius, radiance](Vec3 p) {
            Vec3 to = {position[0] - p[0], position[1] - p[1], position[2] - p[2]};
            double d2 = to[0] * to[0] + to[1] * to[1] + to[2] * to[2], d = std::sqrt(d2);
            // A sphere fully above the horizon: E = pi L (r/d)^2 cos(theta).
            return LightAtPoint{scale(to, 1.0 / d), d, kPi * radiance * radius * radius / d2 * (to[2] / d)};
        };
    }
    bool shadowedAt(Vec3 p) const {
        LightAtPoint l = light(p);
        return std::any_of(occluders.begin(), occluders.end(),
                           [&](const Box& b) { return segmentHitsBox(p, l.toLight, l.distance, b); });
    }
    // Every point of the pixel's neighbourhood (a 5x5 grid over +-kMarginPixels) agrees:
    // 1 shadowed, 0 lit, nullopt mixed (or not all on the ground).
    std::optional<bool> classify(int x, int y) const {
        int shadowed = 0, samples = 0;
        for (int j = 0; j <= 4; ++j)
            for (int i = 0; i <= 4; ++i) {
                double px = x + 0.5 + kMarginPixels * (i - 2) / 2.0, py = y + 0.5 + kMarginPixels * (j - 2) / 2.0;
                auto g = camera.ground(px, py);
                if (!g) return std::nullopt;
                shadowed += shadowedAt(*g) ? 1 : 0;
                ++samples;
            }
        if (shadowed == samples) return true;
        if (shadowed == 0) return false;
        return std::nullopt;
    }

    struct Render {
        std::vector<float> color;
        std::vector<int32_t> id;
    };
    Render render() {
        EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}, {"primId", "/Buffers/id"}}), OBSCURA_OK)
            << host.lastError();
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
        EXPECT_EQ(host.api().getPrimId(host.delegate(), "/Ground", &groundId), OBSCURA_OK);
        return {host.readFloats("/Buffers/color"), host.readInts("/Buffers/id")};
    }
    double expectedLit(int x, int y) const {
        auto g = camera.ground(x + 0.5, y + 0.5);
        return kAlbedo / kPi * light(*g).irradiance;
    }
};

struct Verdict {
    int shadowedPixels = 0, litPixels = 0;
    double worstShadowed = 0.0;  // largest radiance in a shadowed pixel, relative to the lit value
    double worstLit = 0.0;       // largest error of a lit pixel, relative to its analytic value
};

// Checks every ground pixel the CPU classifies against the lit radiance `expected(x, y)` (by
// default the analytic Lambert value); `region` limits the check to some ground points.
using Expectation = std::function<double(int, int)>;
Verdict checkPixels(const ShadowScene& s, const ShadowScene::Render& r, const std::function<bool(Vec3)>& region,
                    const Expectation& expectedLit) {
    Verdict v;
    for (int y = 0; y < s.camera.height; ++y)
        for (int x = 0; x < s.camera.width; ++x) {
            size_t i = size_t(y) * s.camera.width + x;
            if (r.id[i] != s.groundId) continue;
            auto verdict = s.classify(x, y);
            auto g = s.camera.ground(x + 0.5, y + 0.5);
            if (!verdict || !region(*g)) continue;
            double expected = expectedLit(x, y);
            double red = r.color[i * 4];
            if (*verdict) {
                ++v.shadowedPixels;
                v.worstShadowed = std::max(v.worstShadowed, red / expected);
                EXPECT_LE(red, 0.01 * expected) << "shadowed pixel (" << x << ", " << y << ")";
            } else {
                ++v.litPixels;
                double tolerance = 0.01 * expected + smallFloatStep(float(expected), 6);
                v.worstLit = std::max(v.worstLit, std::abs(red - expected) / expected);
                EXPECT_NEAR(red, expected, tolerance) << "lit pixel (" << x << ", " << y << ")";
            }
        }
    return v;
}

Verdict checkPixels(const ShadowScene& s, const ShadowScene::Render& r,
                    const std::function<bool(Vec3)>& region = [](Vec3) { return true; }) {
    return checkPixels(s, r, region, [&s](int x, int y) { return s.expectedLit(x, y); });
}

void print(const char* name, const Verdict& v) {
    std::printf("[ metric ] %s: %d shadowed pixels (worst %.5f of lit), %d lit pixels (worst error %.4f)\n", name,
                v.shadowedPixels, v.worstShadowed, v.litPixels, v.worstLit);
}

// Looking straight down at a ground plane from 5 units: a box at height 1..1.2 under a distant
// light tilted 45 degrees in x casts its shadow 1..1.2 units to +x, apart from the box itself.
PinholeCamera topDownCamera() { return {translation(0, 0, 5), 50.0, 20.955, kWidth, kHeight}; }

void addBoxUnderTheSun(ShadowScene& s, std::map<std::string, HostValue> lightExtra = {}) {
    s.addOccluder("/Box", {{-1.5, -0.5, 1.0}, {-0.5, 0.5, 1.2}});
    s.addDistantLight({1.0, 0.0, -1.0}, 3.0, lightExtra);
}

TEST(Shadows, BoxShadowsTheGroundUnderADistantLight) {
    ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
    addBoxUnderTheSun(s);
    auto r = s.render();
    Verdict v = checkPixels(s, r);
    print("distant light, box", v);
    EXPECT_GT(v.shadowedPixels, 200);
    EXPECT_GT(v.litPixels, 1500);
}

TEST(Shadows, ShadowEdgeLiesWhereTheOccluderProjects) {
    ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
    addBoxUnderTheSun(s);
    auto r = s.render();
    // Along the middle row the shadow spans ground x in [-0.5, 0.7]: the box's faces at heights
    // 1 and 1.2 shifted by their height along the light. Its far edge, x = 0.7, is the projected
    // edge of the top face. Find where the measured share of the light crosses one half, and the
    // predicted edge by bisection on the CPU classification.
    int y = kHeight / 2;
    auto share = [&](int x) {
        size_t i = size_t(y) * kWidth + x;
        return r.color[i * 4] / s.expectedLit(x, y);
    };
    double measured = -1.0;
    for (int x = kWidth / 2; x + 1 < kWidth; ++x)
        if (share(x) < 0.5 && share(x + 1) >= 0.5) {
            // Pixel centres at x + 0.5: interpolate the crossing linearly.
            measured = x + 0.5 + (0.5 - share(x)) / (share(x + 1) - share(x));
            break;
        }
    double lo = kWidth / 2.0, hi = kWidth - 1.0;
    for (int i = 0; i < 60; ++i) {
        double mid = 0.5 * (lo + hi);
        (s.shadowedAt(*s.camera.ground(mid, y + 0.5)) ? lo : hi) = mid;
    }
    double predicted = 0.5 * (lo + hi);
    std::printf("[ metric ] shadow edge: measured %.3f px, predicted %.3f px, error %.3f px\n", measured, predicted,
                measured - predicted);
    ASSERT_GE(measured, 0.0) << "no shadow edge found in the middle row";
    EXPECT_NEAR(measured, predicted, 0.75);
}

void setShadows(TestHost& host, bool on) {
    int32_t flag = on ? 1 : 0;
    ObscuraValue value{OBSCURA_VALUE_BOOL, 0, 1, &flag};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "shadows", &value), OBSCURA_OK);
}

// Acne darkens lit pixels in patterns; with nothing between the light and the plane every pixel
// must keep the radiance it has without shadows, to one step of the accumulation format. (Against
// the analytic value the plane's 8-bit normal adds up to 0.3 degrees of error, 2.4% at 75 degrees
// of incidence: the unshadowed render is the sharper reference.)
void expectNoAcne(ShadowScene& s, const char* name) {
    auto shadowed = s.render();
    setShadows(s.host, false);
    auto unshadowed = s.render();
    double worst = 0.0;
    int checked = 0;
    for (size_t i = 0; i < shadowed.id.size(); ++i) {
        if (shadowed.id[i] != s.groundId) continue;
        float want = unshadowed.color[i * 4];
        worst = std::max(worst, double(std::abs(shadowed.color[i * 4] - want) / want));
        EXPECT_NEAR(shadowed.color[i * 4], want, smallFloatStep(want, 6)) << "pixel " << i % kWidth << ", " << i / kWidth;
        ++checked;
    }
    std::printf("[ metric ] %s: %d lit pixels, worst relative change from the unshadowed render %.5f\n", name, checked,
                worst);
    EXPECT_EQ(checked, kWidth * kHeight);
}

TEST(Shadows, NoAcneOnLitPlanesAtGrazingAngles) {
    {
        // The sun 75 degrees from the plane's normal.
        ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
        double theta = 75.0 * kPi / 180.0;
        s.addDistantLight({std::sin(theta), 0.3, -std::cos(theta)}, 3.0);
        expectNoAcne(s, "distant light at 75 degrees");
    }
    {
        // A sphere light 0.3 units above the plane: up to 80 degrees at the image's corners.
        ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
        s.addSphereLight({0.2, -0.1, 0.3}, 0.01, 4000.0);
        expectNoAcne(s, "sphere light 0.3 above the plane");
    }
}

TEST(Shadows, ShadowEnableFalseAndTheShadowsSettingRemoveTheShadow) {
    {
        ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
        addBoxUnderTheSun(s, {{"inputs:shadow:enable", HostValue::boolean(false)}});
        s.occluders.clear();  // the light ignores the box: everything it reaches is lit
        Verdict v = checkPixels(s, s.render());
        print("inputs:shadow:enable false", v);
        EXPECT_EQ(v.shadowedPixels, 0);
        EXPECT_GT(v.litPixels, 3000);
    }
    {
        ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
        addBoxUnderTheSun(s);
        setShadows(s.host, false);
        s.occluders.clear();
        Verdict v = checkPixels(s, s.render());
        print("render setting shadows off", v);
        EXPECT_GT(v.litPixels, 3000);
    }
}

TEST(Shadows, SphereLightShadowsTheGround) {
    // A small bulb 3 units up at x = 1.5 and a box at height 1..1.1 between it and the ground:
    // the shadow is the box's outline scaled 1.5x about the point below the light.
    ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
    s.addOccluder("/Box", {{0.25, -0.25, 1.0}, {0.75, 0.25, 1.1}});
    s.addSphereLight({1.5, 0.0, 3.0}, 0.01, 40000.0);
    Verdict v = checkPixels(s, s.render());
    print("sphere light, box", v);
    EXPECT_GT(v.shadowedPixels, 150);
    EXPECT_GT(v.litPixels, 1500);
}

TEST(Shadows, SpotLightShadowsTheGround) {
    // The sphere light of SphereLightShadowsTheGround, shaped into a 50-degree cone pointing down:
    // one perspective map instead of a cube. Every visible ground point lies within 43 degrees of
    // the axis, where the cone leaves the light unchanged.
    ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
    s.addOccluder("/Box", {{0.25, -0.25, 1.0}, {0.75, 0.25, 1.1}});
    s.addSphereLight({1.5, 0.0, 3.0}, 0.01, 40000.0,
                     {{"inputs:shaping:cone:angle", HostValue::floatValue(50.0f)},
                      {"inputs:shaping:cone:softness", HostValue::floatValue(0.0f)}});
    Verdict v = checkPixels(s, s.render());
    print("spot light (50-degree cone), box", v);
    EXPECT_GT(v.shadowedPixels, 150);
    EXPECT_GT(v.litPixels, 1500);
}

TEST(Shadows, RectLightShadowsTheGround) {
    // A small rectangle facing down 3 units up: a cube of maps around its centre. Its lit pixels
    // must keep the radiance they have with the box hidden (the area-light shading is
    // area_light_test.cpp's), its shadowed ones lose it.
    ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
    s.addOccluder("/Box", {{0.25, -0.25, 1.0}, {0.75, 0.25, 1.1}});
    const Vec3 centre = {1.5, 0.0, 3.0};
    s.host.addPrim("rectLight", "/Panel",
                   {{"inputs:intensity", HostValue::floatValue(40000.0f)},
                    {"inputs:width", HostValue::floatValue(0.02f)},
                    {"inputs:height", HostValue::floatValue(0.02f)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   translation(centre[0], centre[1], centre[2]));
    // Classification treats the small rectangle as a point at its centre.
    s.light = [centre](Vec3 p) {
        Vec3 to = {centre[0] - p[0], centre[1] - p[1], centre[2] - p[2]};
        double d = std::sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
        return LightAtPoint{scale(to, 1.0 / d), d, 0.0};
    };
    auto r = s.render();
    s.host.set("/Box", "visibility", HostValue::token("invisible"));
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Box", OBSCURA_DIRTY_VISIBILITY), OBSCURA_OK);
    auto unoccluded = s.render();
    Verdict v = checkPixels(s, r, [](Vec3) { return true; },
                            [&](int x, int y) { return double(unoccluded.color[(size_t(y) * kWidth + x) * 4]); });
    print("rect light, box", v);
    EXPECT_GT(v.shadowedPixels, 150);
    EXPECT_GT(v.litPixels, 1500);
}

TEST(Shadows, OpacityCutoutsCastShapedShadows) {
    // A quad whose opacity texture is transparent on its left half (u < 0.5, opacityThreshold
    // 0.5): only the right half, x in [-1, -0.5], casts; the left half's shadow region stays lit.
    std::filesystem::path mask =
        std::filesystem::temp_directory_path() / ("obscura_shadow_mask_" + std::to_string(getpid()) + ".png");
    std::vector<uint8_t> texels;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) texels.insert(texels.end(), 3, x < 4 ? 0 : 255);
    ASSERT_FALSE(image::isError(image::writePng(mask.string(), 8, 8, image::PngFormat::Rgb, texels.data(), 24)));
    ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
    s.host.addPrim("material", "/Looks/Mask",
                   {{"inputs:diffuseColor", HostValue::float3(kAlbedo, kAlbedo, kAlbedo)},
                    {"inputs:opacityThreshold", HostValue::floatValue(0.5f)},
                    {"obscura:opacity:file", HostValue::token(mask.string())},
                    {"obscura:opacity:sourceColorSpace", HostValue::token("raw")}});
    HostValue st = HostValue::float2Array({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    s.host.addPrim("mesh", "/Leaf",
                   {{"points", HostValue::points({{-1.5f, -0.5f, 1}, {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {-1.5f, 0.5f, 1}})},
                    {"faceVertexCounts", HostValue::intArray({4})},
                    {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                    {"subdivisionScheme", HostValue::token("none")},
                    {"primvars:st", st},
                    {"material:binding", HostValue::path("/Looks/Mask")}});
    s.occluders.push_back({{-1.0, -0.5, 1.0}, {-0.5, 0.5, 1.0}});
    s.addDistantLight({1.0, 0.0, -1.0}, 3.0);
    auto r = s.render();
    std::filesystem::remove(mask);
    Verdict v = checkPixels(s, r);
    Verdict underTheCutHalf = checkPixels(s, r, [](Vec3 p) { return p[0] > -0.45 && p[0] < -0.05 && std::abs(p[1]) < 0.45; });
    print("opacity cut-out, the whole ground", v);
    print("opacity cut-out, where the transparent half would shadow", underTheCutHalf);
    EXPECT_GT(v.shadowedPixels, 150);
    EXPECT_GT(underTheCutHalf.litPixels, 100);
}

TEST(Shadows, CascadesShadowTheGroundNearAndFar) {
    // A long ground plane seen at a slant; the sun at 45 degrees; one box close to the camera and
    // one far along the plane: their shadows land in different cascades.
    PinholeCamera cam{lookingAlongY({0, 0, 8}, 30.0), 12.0, 20.955, 160, 120};
    ShadowScene s(cam, 60.0, -5.0, 300.0);
    s.addOccluder("/Near", {{-3.0, 6.0, 2.0}, {-1.0, 10.0, 2.5}});
    s.addOccluder("/Far", {{-20.0, 45.0, 12.0}, {-6.0, 125.0, 13.0}});
    s.addDistantLight({1.0, 0.0, -1.0}, 3.0);
    auto r = s.render();
    Verdict nearShadow = checkPixels(s, r, [](Vec3 p) { return p[1] < 20.0; });
    Verdict farShadow = checkPixels(s, r, [](Vec3 p) { return p[1] > 40.0; });
    print("cascades, ground closer than 20 units", nearShadow);
    print("cascades, ground beyond 40 units", farShadow);
    EXPECT_GT(nearShadow.shadowedPixels, 50);
    EXPECT_GT(farShadow.shadowedPixels, 30);
    EXPECT_GT(nearShadow.litPixels + farShadow.litPixels, 5000);
}

TEST(Shadows, ResolutionOutsideItsRangeIsRefused) {
    TestHost host;
    int32_t tiny = 8;
    ObscuraValue value{OBSCURA_VALUE_INT, 0, 1, &tiny};
    EXPECT_EQ(host.api().setRenderSetting(host.delegate(), "shadows:resolution", &value), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(host.lastError().find("outside 64..4096"), std::string::npos) << host.lastError();
    int32_t five = 5;
    value.data = &five;
    EXPECT_EQ(host.api().setRenderSetting(host.delegate(), "shadows:cascades", &value), OBSCURA_ERROR_INVALID_ARGUMENT);
}

TEST(Shadows, UsdaHostServesShadowEnable) {
    // UsdLuxShadowAPI's input as authored, and under its name before UsdLux 21.02 (no "inputs:").
    auto opened = usda::Stage::openFromString(R"(#usda 1.0
def DistantLight "Sun"
{
    bool inputs:shadow:enable = 0
}
def SphereLight "Bulb"
{
    bool shadow:enable = 0
}
def SphereLight "Default"
{
}
)",
                                              "inline.usda");
    ASSERT_TRUE(std::holds_alternative<std::unique_ptr<usda::Stage>>(opened));
    harness::UsdSceneHost host(*std::get<std::unique_ptr<usda::Stage>>(opened));
    const ObscuraSceneDelegate& sd = host.sceneDelegate();
    for (const char* path : {"/Sun", "/Bulb"}) {
        ObscuraValue value{};
        ASSERT_EQ(sd.getValue(sd.userData, path, "inputs:shadow:enable", 0.0, &value), OBSCURA_OK) << path;
        ASSERT_EQ(value.type, OBSCURA_VALUE_BOOL);
        EXPECT_EQ(*static_cast<const int32_t*>(value.data), 0) << path;
    }
    // Not authored: the delegate falls back to the schema's default (on).
    ObscuraValue value{};
    EXPECT_NE(sd.getValue(sd.userData, "/Default", "inputs:shadow:enable", 0.0, &value), OBSCURA_OK);
}

}  // namespace
}  // namespace obscura::test

namespace obscura::test {
namespace {

// The atlas is kept between frames: a frame where nothing that casts or lights changed renders no
// shadow map, and a frame after an edit renders the views it touched — the shadows must then be
// where the moved box and the turned light put them, to the same analytic bar as a first frame.
TEST(Shadows, KeptAtlasRendersNothingWhenStaticAndFollowsEveryEdit) {
    ShadowScene s(topDownCamera(), 10.0, -10.0, 10.0);
    // Every frame through the pixel centres: frames differ only by what the shadow atlas holds.
    setNumber(s.host, "taa", 0.0);
    addBoxUnderTheSun(s);
    Verdict first = checkPixels(s, s.render());
    EXPECT_TRUE(ranPass(s.host, "shadow_maps"));
    EXPECT_GT(first.shadowedPixels, 200);

    Verdict unchanged = checkPixels(s, s.render());
    EXPECT_FALSE(ranPass(s.host, "shadow_maps")) << "nothing changed, yet the shadow map was rendered again";
    EXPECT_EQ(unchanged.shadowedPixels, first.shadowedPixels);

    // The box moves 0.3 units along +y: its old shadow's edge must be lit, its new one dark.
    s.host.setTransform("/Box", translation(0, 0.3, 0));
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Box", OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    for (Box& box : s.occluders) box.min[1] += 0.3, box.max[1] += 0.3;
    Verdict moved = checkPixels(s, s.render());
    print("kept atlas, box moved", moved);
    EXPECT_TRUE(ranPass(s.host, "shadow_maps"));
    EXPECT_GT(moved.shadowedPixels, 200);

    // The sun turns to travel along -y: the shadow falls on another side of the box.
    const Vec3 travel = normalize({0.0, -1.0, -1.0});
    s.host.setTransform("/Sun", lightPointingAlong(travel));
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Sun", OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    s.light = [travel](Vec3) { return LightAtPoint{scale(travel, -1.0), 1e30, 3.0 * -travel[2]}; };
    Verdict turned = checkPixels(s, s.render());
    print("kept atlas, light turned", turned);
    EXPECT_TRUE(ranPass(s.host, "shadow_maps"));
    EXPECT_GT(turned.shadowedPixels, 100);

    checkPixels(s, s.render());
    EXPECT_FALSE(ranPass(s.host, "shadow_maps"));

    // The kept atlas goes with the delegate: destruction leaves no object behind (validation).
    ASSERT_EQ(s.host.destroyDelegate(), OBSCURA_OK);
    EXPECT_TRUE(s.host.loggedErrors().empty()) << s.host.loggedErrors().front();
}

}  // namespace
}  // namespace obscura::test
