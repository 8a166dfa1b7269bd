// The reference mode's points on a light's emitter (delegate/prims/light.h emitterSample) over the
// reference sub-frames' emitter coordinates: a distant light's directions fill its cone uniformly in
// solid angle; a sphere's, rect's and disk's points lie on the surface and their mean irradiance is
// the closed form of the whole emitter.
#include "delegate/prims/light.h"
#include "delegate/reference_frames.h"

#include <gtest/gtest.h>

#include <numbers>

namespace obscura::delegate {
namespace {

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

// The mean over the sub-frames of a surface point's irradiance E = L A cos(emitter) cos(receiver) / d^2
// at `receiver` (normal `normal`), as light_evaluation.glsl evaluates LIGHT_SURFACE_SAMPLE.
double meanIrradiance(const passes::LightData& light, Vec3d receiver, Vec3d normal, Vec3d centre, double size) {
    double sum = 0.0;
    auto points = emitterPoints(4096);
    for (const auto& u : points) {
        passes::LightData p = emitterSample(light, u);
        EXPECT_EQ(p.positionType[3], float(passes::LightType::SurfaceSample));
        Vec3d at = xyz(p.positionType);
        EXPECT_LE(length(sub(at, centre)), size * (1.0 + 1e-5)) << "on the emitter";
        Vec3d toLight = sub(at, receiver);
        double d = length(toLight);
        Vec3d L = scale(toLight, 1.0 / d);
        double cosEmitter = std::max(0.0, -dot(xyz(p.axisX), L)), cosReceiver = std::max(0.0, dot(normal, L));
        sum += p.radiance[0] * cosEmitter * cosReceiver / (d * d);
    }
    return sum / double(points.size());
}

TEST(EmitterSample, SpherePointsAddUpToTheSpheresIrradiance) {
    const double radius = 0.5, radiance = 3.0, height = 2.0;
    passes::LightData bulb{};
    bulb.positionType = {0, 0, float(height), float(passes::LightType::Sphere)};
    bulb.directionAngle = {0, 0, -1, 0};
    bulb.radiance = {float(radiance), float(radiance), float(radiance), float(radius)};
    bulb.factors = {1, 1, 0, 10};
    bulb.shaping = {float(kPi), float(kPi), 0, 0};
    // A receiver facing the sphere's centre from `height`, and one tilted by 60 degrees (the
    // sphere above its horizon): E = pi L (r/d)^2 cos(theta).
    for (double tilt : {0.0, 60.0}) {
        double t = tilt * kPi / 180.0;
        double expected = kPi * radiance * radius * radius / (height * height) * std::cos(t);
        double measured = meanIrradiance(bulb, {0, 0, 0}, {std::sin(t), 0, std::cos(t)}, {0, 0, height}, radius);
        std::printf("[ metric ] sphere light, receiver tilted %.0f deg: mean %.5f, closed form %.5f\n", tilt, measured,
                    expected);
        EXPECT_NEAR(measured, expected, 0.01 * expected);
    }
    EXPECT_FLOAT_EQ(emitterSample(bulb, {0.3, 0.7}).factors[3], 10.5f) << "the influence range grows by the radius";
    bulb.factors[2] = 1.0f;  // treatAsPoint
    EXPECT_EQ(emitterSample(bulb, {0.3, 0.7}).positionType, bulb.positionType);
}

TEST(EmitterSample, RectAndDiskPointsAddUpToTheirIrradiance) {
    // Facing down at height h above the receiver's point: a disk of radius r gives
    // E = pi L r^2 / (h^2 + r^2); a square of half side a, 4 L (a^2 / sqrt(...)) from the corner factor.
    const double h = 1.0, radiance = 2.0;
    passes::LightData disk{};
    disk.positionType = {0, 0, float(h), float(passes::LightType::Disk)};
    disk.directionAngle = {0, 0, -1, 0};
    disk.radiance = {float(radiance), float(radiance), float(radiance), 0};
    disk.axisX = {0.5f, 0, 0, 0};
    disk.axisY = {0, 0.5f, 0, 0};
    disk.shaping = {float(kPi), float(kPi), 0, 0};
    double r = 0.5, expectedDisk = kPi * radiance * r * r / (h * h + r * r);
    double measuredDisk = meanIrradiance(disk, {0, 0, 0}, {0, 0, 1}, {0, 0, h}, r);
    passes::LightData rect = disk;
    rect.positionType[3] = float(passes::LightType::Rect);
    // Configuration factor of a parallel square of half side a centred above (four corner factors).
    double A = 0.5 / h, s = std::sqrt(1 + A * A);
    double expectedRect = kPi * radiance * 4.0 * (2.0 * A / s * std::atan(A / s)) / (2.0 * kPi);
    double measuredRect = meanIrradiance(rect, {0, 0, 0}, {0, 0, 1}, {0, 0, h}, 0.5 * std::sqrt(2.0));
    std::printf("[ metric ] disk light: mean %.5f, closed form %.5f; rect light: mean %.5f, closed form %.5f\n",
                measuredDisk, expectedDisk, measuredRect, expectedRect);
    EXPECT_NEAR(measuredDisk, expectedDisk, 0.01 * expectedDisk);
    EXPECT_NEAR(measuredRect, expectedRect, 0.01 * expectedRect);
    // One-sided: nothing reaches a receiver behind the emitting face.
    EXPECT_EQ(meanIrradiance(rect, {0, 0, 2.0 * h}, {0, 0, -1}, {0, 0, h}, 0.5 * std::sqrt(2.0)), 0.0);
}

}  // namespace
}  // namespace obscura::delegate
