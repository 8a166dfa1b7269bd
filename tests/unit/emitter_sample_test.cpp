// The reference mode's points on a light's emitter (delegate/prims/light.h emitterSample) over the
// reference sub-frames' emitter coordinates: a distant light's directions fill its cone uniformly in
// solid angle; other lights stay whole.
#include "delegate/prims/light.h"
#include "renderer/reference_frames.h"

#include <gtest/gtest.h>

#include <numbers>

namespace obscura::delegate {
namespace {

using renderer::ReferenceSubFrame;
using renderer::referenceSubFrames;

constexpr double kPi = std::numbers::pi;

std::vector<std::array<double, 2>> emitterPoints(uint32_t count) {
    std::vector<std::array<double, 2>> points;
    for (const ReferenceSubFrame& f : referenceSubFrames(count, {})) {
        EXPECT_GE(f.emitter[0], 0.0);
        EXPECT_LT(f.emitter[0], 1.0);
        EXPECT_GE(f.emitter[1], 0.0);
        EXPECT_LT(f.emitter[1], 1.0);
        points.push_back(f.emitter);
    }
    return points;
}

Vec3d xyz(const std::array<float, 4>& v) { return {v[0], v[1], v[2]}; }

TEST(EmitterSample, DistantDirectionsFillTheConeUniformlyInSolidAngle) {
    const double halfAngle = 2.5 * kPi / 180.0;
    passes::LightData sun{};
    Vec3d axis = normalized({0.3, -1.0, 0.2});
    sun.positionType = {0, 0, 0, float(passes::LightType::Distant)};
    sun.directionAngle = {float(axis[0]), float(axis[1]), float(axis[2]), float(halfAngle)};
    sun.radiance = {2, 2, 2, 0};
    int inner = 0;
    Vec3d mean{};
    auto points = emitterPoints(1024);
    for (const auto& u : points) {
        passes::LightData d = emitterSample(sun, u);
        EXPECT_EQ(d.directionAngle[3], 0.0f) << "each sub-frame's sun is a point";
        EXPECT_EQ(d.radiance[0], 2.0f) << "with the whole light's irradiance";
        Vec3d dir = xyz(d.directionAngle);
        EXPECT_NEAR(length(dir), 1.0, 1e-6);
        double angle = std::acos(std::min(1.0, dot(dir, axis)));
        EXPECT_LE(angle, halfAngle * 1.0001);
        // Uniform in solid angle: the cone of half the solid angle has cos = (1 + cos a) / 2.
        if (std::cos(angle) >= 0.5 * (1.0 + std::cos(halfAngle))) ++inner;
        mean = add(mean, dir);
    }
    std::printf("[ metric ] 1024 sun directions: %d within the half solid angle\n", inner);
    EXPECT_NEAR(inner, 512, 16);
    EXPECT_NEAR(dot(normalized(mean), axis), 1.0, 1e-6) << "centred on the axis";
    // No angle: the light as it is.
    sun.directionAngle[3] = 0.0f;
    EXPECT_EQ(emitterSample(sun, {0.3, 0.7}).directionAngle, sun.directionAngle);
}

TEST(EmitterSample, LocalLightsAndDomesStayWhole) {
    for (auto type : {passes::LightType::Sphere, passes::LightType::Rect, passes::LightType::Disk, passes::LightType::Dome}) {
        passes::LightData light{};
        light.positionType = {1, 2, 3, float(type)};
        light.radiance = {1, 1, 1, 0.5f};
        passes::LightData sampled = emitterSample(light, {0.3, 0.7});
        EXPECT_EQ(sampled.positionType, light.positionType);
        EXPECT_EQ(sampled.radiance, light.radiance);
    }
}

}  // namespace
}  // namespace obscura::delegate
