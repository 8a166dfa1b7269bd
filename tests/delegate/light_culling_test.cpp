// The lighting pass's light culling (lighting.comp: tiles, then 2.5D depth slices) drops a light
// only where it cannot reach: many small lights sum as every light at every pixel, and a tile that
// spans a card two units from the camera and a floor five hundred units behind it lights each
// surface with its own light, at the analytic radiance, though neither light's influence range
// reaches the other surface's depth. Disks and spots are culled to their Lambert lobes and cones
// (light_evaluation.glsl lightReaches), and many of each still sum like every light at every pixel.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

namespace obscura::test {
namespace {

// Radiance of a Lambert surface of albedo kLitPlaneAlbedo facing +Z at `p` under a sphere light
// of radiance `radiance` and radius `radius` at `light`: E = pi L (r/d)^2 cos(theta).
double lambertUnderSphere(std::array<double, 3> p, std::array<double, 3> light, double radiance, double radius) {
    const double dx = light[0] - p[0], dy = light[1] - p[1], dz = light[2] - p[2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    const double cosTheta = dz / std::sqrt(d2);
    return kLitPlaneAlbedo / kPi * (kPi * radiance * radius * radius / d2 * cosTheta);
}

// The Lambert plane's red radiance at pixel (x, y) equals that of `irradiance` (every light's),
// less at most that of `droppable` (the lights culling may drop there), within 1% and a step of
// the accumulation format.
::testing::AssertionResult withinCulledSum(const std::vector<float>& color, int x, int y, double irradiance,
                                           double droppable) {
    const double l = kLitPlaneAlbedo / kPi * irradiance, step = smallFloatStep(float(l), 6);
    const float got = color[(size_t(y) * kWidth + x) * 4];
    if (got <= l + 0.01 * l + step && got >= l - 0.01 * l - step - kLitPlaneAlbedo / kPi * droppable)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "pixel " << x << ", " << y << ": " << got << " outside ["
                                         << l - kLitPlaneAlbedo / kPi * droppable << ", " << l << "] and its tolerance";
}

TEST(TiledLightCulling, EachSurfaceOfATileSpanningTwoDepthsGetsItsOwnLight) {
    const double cameraHeight = 500.0, cardHeight = 498.0, cardEdge = 0.1;
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, cameraHeight), kLitPlaneFocalLength, kLitPlaneAperture);
    addMaterial(host, "/Looks/Grey", {kLitPlaneAlbedo, kLitPlaneAlbedo, kLitPlaneAlbedo});
    addPlane(host, "/Floor", "/Looks/Grey", 200.0);
    // The card covers x <= cardEdge: its edge crosses pixel column 39, inside the tile of columns 32-47.
    addPlane(host, "/Card", "/Looks/Grey", 1.0, translation(cardEdge - 1.0, 0, cardHeight));
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);

    // Each light's influence range (delegate/prims/light.cpp: irradiance above 2^-12) is about 57
    // units: the floor's light stops far short of the card and the card's far short of the floor.
    const double radiance = 100.0, radius = 0.05;
    const int floorX = 44, cardX = 35, y = 36;
    const auto floorPoint = planePointAtPixel(floorX, y, cameraHeight, kLitPlaneTanHalfFov);
    const std::array<double, 3> floorLight{floorPoint[0], floorPoint[1], 0.5};
    const std::array<double, 3> cardLight{0.0, 0.0, cardHeight + 0.5};
    for (const auto& [path, at] : {std::pair{"/FloorBulb", floorLight}, std::pair{"/CardBulb", cardLight}})
        host.addPrim("sphereLight", path,
                     {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                      {"inputs:radius", HostValue::floatValue(float(radius))},
                      {"inputs:specular", HostValue::floatValue(0.0f)}},
                     translation(at[0], at[1], at[2]));
    ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    const std::vector<float> color = host.readFloats("/Buffers/color");

    const double onFloor = lambertUnderSphere(floorPoint, floorLight, radiance, radius);
    expectRadiance(color, floorX, y, {onFloor, onFloor, onFloor});
    // The card's pixel seen at two units: its point from the pixel's ray.
    auto cardPoint = planePointAtPixel(cardX, y, cameraHeight - cardHeight, kLitPlaneTanHalfFov);
    cardPoint[2] = cardHeight;
    ASSERT_LT(cardPoint[0], cardEdge) << "the pixel sees the card";
    const double onCard = lambertUnderSphere(cardPoint, cardLight, radiance, radius);
    expectRadiance(color, cardX, y, {onCard, onCard, onCard});
}

TEST(TiledLightCulling, ManySmallLightsSumLikeEveryLightAtEveryPixel) {
    // 300 dim lights close to the plane: each one's influence range (where its irradiance bound
    // L * pi r^2 / d^2 falls to 2^-12) spans a few tiles, so tiles keep different lists. Every
    // pixel must equal the analytic sum over all lights, less at most the lights culling was
    // allowed to drop: those whose bound at that pixel is below the threshold.
    LitPlaneScene s;
    struct Bulb { double x, y, h, r, radiance; };
    std::vector<Bulb> bulbs;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> across(-1.2, 1.2), height(0.03, 0.15), level(0.02, 0.06);
    for (int i = 0; i < 300; ++i) {
        Bulb b{across(rng), across(rng), height(rng), 0.02, level(rng)};
        bulbs.push_back(b);
        s.host.addPrim("sphereLight", "/Bulbs/b" + std::to_string(i),
                       {{"inputs:intensity", HostValue::floatValue(float(b.radiance))},
                        {"inputs:radius", HostValue::floatValue(float(b.r))},
                        {"inputs:specular", HostValue::floatValue(0.0f)}},
                       translation(b.x, b.y, b.h));
    }
    auto color = s.renderColor();
    const double threshold = 1.0 / 4096.0;
    int checked = 0, droppable = 0, pairs = 0;
    double largest = 0;
    for (int y = 0; y < kHeight; y += 3)
        for (int x = 0; x < kWidth; x += 3) {
            auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
            double e = 0, mayDrop = 0;
            for (const Bulb& b : bulbs) {
                double dx = p[0] - b.x, dy = p[1] - b.y, d2 = dx * dx + dy * dy + b.h * b.h;
                double contribution = kPi * b.radiance * b.r * b.r / d2 * (b.h / std::sqrt(d2));
                e += contribution;
                ++pairs;
                if (kPi * b.radiance * b.r * b.r / d2 < threshold) mayDrop += contribution, ++droppable;
            }
            ASSERT_TRUE(withinCulledSum(color, x, y, e, mayDrop));
            largest = std::max(largest, kLitPlaneAlbedo / kPi * e);
            ++checked;
        }
    EXPECT_GT(checked, 400);
    // The scene exercises culling: most light-pixel pairs are out of range, yet lights matter.
    EXPECT_GT(droppable, pairs / 2);
    EXPECT_GT(largest, 1e-3);
    std::printf("tiled culling: %d pixels checked, %.0f%% of light-pixel pairs out of range, peak radiance %.4f\n",
                checked, 100.0 * droppable / pairs, largest);
}

TEST(TiledLightCulling, DisksAndSpotsAreCulledToTheirLobesAndConesOnly) {
    // 150 small disks facing the plane and 150 spot bulbs (cones of 20-60 degrees, hard-edged)
    // close above it. A disk may be dropped only where the bound of its Lambert lobe,
    // L A z / (d - s)^3 (s its half diagonal, z its height), or of its sphere, L A / d^2, is
    // below the threshold; a spot only outside its cone (or beyond its range). Every pixel must
    // equal the analytic sum, less at most what those lights give it.
    LitPlaneScene s;
    const double threshold = 1.0 / 4096.0;
    struct Emitter { bool disk; double x, y, h, r, radiance, cone; };
    std::vector<Emitter> emitters;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> across(-1.2, 1.2), height(0.04, 0.2), level(0.05, 0.15), cone(20, 60);
    for (int i = 0; i < 300; ++i) {
        Emitter e{i % 2 == 0, across(rng), across(rng), height(rng), 0.02, level(rng), cone(rng)};
        emitters.push_back(e);
        std::map<std::string, HostValue> inputs = {
            {"inputs:intensity", HostValue::floatValue(float(e.radiance))},
            {"inputs:radius", HostValue::floatValue(float(e.r))},
            {"inputs:specular", HostValue::floatValue(0.0f)}};
        if (!e.disk) inputs.emplace("inputs:shaping:cone:angle", HostValue::floatValue(float(e.cone)));
        s.host.addPrim(e.disk ? "diskLight" : "sphereLight", "/Lights/l" + std::to_string(i), inputs,
                       translation(e.x, e.y, e.h));
    }
    auto color = s.renderColor();
    int checked = 0, pairs = 0, droppedByShape = 0;
    double largest = 0;
    for (int y = 0; y < kHeight; y += 3)
        for (int x = 0; x < kWidth; x += 3) {
            auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
            double irradiance = 0, mayDrop = 0;
            for (const Emitter& e : emitters) {
                double dx = p[0] - e.x, dy = p[1] - e.y, d = std::sqrt(dx * dx + dy * dy + e.h * e.h);
                double area = kPi * e.r * e.r, range2 = e.radiance * area / threshold;
                double contribution = 0;
                bool droppable = d * d > range2;
                bool shapeDrops = false;
                if (e.disk) {
                    contribution = diskIrradiance(e.radiance, e.r, e.h, std::hypot(dx, dy));
                    double beyond = d - std::sqrt(2.0) * e.r;
                    shapeDrops = beyond > 0 && beyond * beyond * beyond > range2 * e.h;
                } else {
                    double offAxis = std::acos(e.h / d) * 180 / kPi;
                    if (offAxis < e.cone) contribution = kPi * e.radiance * e.r * e.r / (d * d) * (e.h / d);
                    // At the cone's edge either side is right within rounding.
                    shapeDrops = offAxis > e.cone - 1e-3;
                }
                if (shapeDrops && !droppable) ++droppedByShape;
                if (droppable || shapeDrops) mayDrop += contribution;
                irradiance += contribution;
                ++pairs;
            }
            ASSERT_TRUE(withinCulledSum(color, x, y, irradiance, mayDrop));
            largest = std::max(largest, kLitPlaneAlbedo / kPi * irradiance);
            ++checked;
        }
    EXPECT_GT(checked, 400);
    // The scene exercises the shapes: many pairs the spheres keep lie outside a lobe or cone.
    EXPECT_GT(droppedByShape, pairs / 8);
    EXPECT_GT(largest, 1e-3);
    std::printf("disks and spots: %d pixels checked, %.0f%% of light-pixel pairs culled by lobe or cone only, "
                "peak radiance %.4f\n",
                checked, 100.0 * droppedByShape / pairs, largest);
}

}  // namespace
}  // namespace obscura::test
