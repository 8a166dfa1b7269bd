// Cascaded shadow map math (delegate/shadow_cascades.h): the practical split scheme covers the
// view range in order; every cascade contains its frustum slice; cascades are stable (Valient
// 2008): moving the camera moves a cascade by whole texels, turning it keeps its size; cube faces
// cover every direction around a sphere light with a guard band.
#include "delegate/shadow_cascades.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::delegate {
namespace {

constexpr uint32_t kResolution = 1024;

// A perspective camera at `eye`, turned by `yawDegrees` about Y and pitched by `pitchDegrees`
// (as Camera::viewMatrix and Camera::projectionMatrix build them: Vulkan clip space, y down).
ShadowedCamera camera(Vec3d eye, double yawDegrees, double pitchDegrees, double near = 0.5, double far = 500.0) {
    const double yaw = yawDegrees * std::numbers::pi / 180.0, pitch = pitchDegrees * std::numbers::pi / 180.0;
    // cameraToWorld = rotateX(pitch) * rotateY(yaw) * translate(eye), row vectors.
    Matrix4d rx = {1, 0, 0, 0, 0, std::cos(pitch), std::sin(pitch), 0, 0, -std::sin(pitch), std::cos(pitch), 0, 0, 0, 0, 1};
    Matrix4d ry = {std::cos(yaw), 0, -std::sin(yaw), 0, 0, 1, 0, 0, std::sin(yaw), 0, std::cos(yaw), 0, 0, 0, 0, 1};
    Matrix4d cameraToWorld = multiply(rx, ry);
    cameraToWorld[12] = eye[0];
    cameraToWorld[13] = eye[1];
    cameraToWorld[14] = eye[2];
    ShadowedCamera c;
    invert(cameraToWorld, c.view);
    // 50 mm lens on a 36 x 24 mm aperture, 16:9 image (fit widens the horizontal aperture).
    double tanY = 12.0 / 50.0, tanX = tanY * 16.0 / 9.0;
    c.projection = transpose(Matrix4d{1.0 / tanX, 0, 0, 0, 0, -1.0 / tanY, 0, 0, 0, 0, far / (near - far),
                                      near * far / (near - far), 0, 0, -1, 0});
    return c;
}

std::array<double, 4> clipOf(const Vec3d& p, const Matrix4d& m) {
    std::array<double, 4> c{};
    for (size_t j = 0; j < 4; ++j) c[j] = p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + m[12 + j];
    return c;
}

const Vec3d kSun = normalized({0.4, -1.0, 0.3});
Aabb sceneBounds() {
    Aabb box;
    box.extend({-300, -1, -300});
    box.extend({300, 40, 300});
    return box;
}

TEST(ShadowCascades, SplitsAreMonotonicAndCoverNearToFar) {
    for (double lambda : {0.0, 0.5, 0.75, 1.0}) {
        auto splits = cascadeSplits(0.5, 500.0, 4, lambda);
        ASSERT_EQ(splits.size(), 5u);
        EXPECT_EQ(splits.front(), 0.5);
        EXPECT_EQ(splits.back(), 500.0);
        for (size_t i = 1; i < splits.size(); ++i) EXPECT_LT(splits[i - 1], splits[i]) << "lambda " << lambda;
    }
    // The two schemes it blends: uniform at lambda 0, logarithmic at 1.
    auto uniform = cascadeSplits(1.0, 9.0, 2, 0.0), logarithmic = cascadeSplits(1.0, 9.0, 2, 1.0);
    EXPECT_NEAR(uniform[1], 5.0, 1e-12);
    EXPECT_NEAR(logarithmic[1], 3.0, 1e-12);
}

TEST(ShadowCascades, EveryFrustumSliceCornerLiesInsideItsCascade) {
    ShadowedCamera cam = camera({10, 20, 30}, 35.0, -20.0);
    auto splits = cascadeSplits(0.5, 500.0, 4, 0.75);
    for (size_t i = 0; i + 1 < splits.size(); ++i) {
        Cascade cascade = fitStableCascade(cam, splits[i], splits[i + 1], kSun, sceneBounds(), kResolution);
        double worstMargin = 1e30;
        for (const Vec3d& corner : frustumSliceCorners(cam, splits[i], splits[i + 1])) {
            auto c = clipOf(corner, cascade.viewProjection);
            EXPECT_NEAR(c[3], 1.0, 1e-12) << "orthographic";
            EXPECT_LE(std::abs(c[0]), 1.0) << "cascade " << i;
            EXPECT_LE(std::abs(c[1]), 1.0) << "cascade " << i;
            EXPECT_GE(c[2], 0.0);
            EXPECT_LE(c[2], 1.0);
            worstMargin = std::min(worstMargin, 1.0 - std::max(std::abs(c[0]), std::abs(c[1])));
            // The bounding sphere holds the corner too.
            Vec3d d = {corner[0] - cascade.sphereCenter[0], corner[1] - cascade.sphereCenter[1],
                       corner[2] - cascade.sphereCenter[2]};
            EXPECT_LE(length(d), cascade.sphereRadius * (1.0 + 1e-9));
        }
        std::printf("[ metric ] cascade %zu: slice %.2f..%.2f, sphere radius %.3f, texel %.4f, worst corner margin %.4f\n",
                    i, splits[i], splits[i + 1], cascade.sphereRadius, cascade.texelWorldSize, worstMargin);
    }
}

TEST(ShadowCascades, CastersBetweenTheLightAndTheSliceAreInDepthRange) {
    ShadowedCamera cam = camera({0, 5, 0}, 0.0, -10.0);
    Cascade cascade = fitStableCascade(cam, 0.5, 20.0, kSun, sceneBounds(), kResolution);
    for (const Vec3d& corner : sceneBounds().corners()) {
        double z = clipOf(corner, cascade.viewProjection)[2];
        EXPECT_GE(z, -1e-9);
        EXPECT_LE(z, 1.0 + 1e-9);
    }
}

TEST(ShadowCascades, SubTexelCameraMotionMovesTheCascadeByWholeTexels) {
    auto splits = cascadeSplits(0.5, 500.0, 4, 0.75);
    for (size_t i = 0; i < 4; ++i) {
        Cascade before = fitStableCascade(camera({10, 20, 30}, 35.0, -20.0), splits[i], splits[i + 1], kSun,
                                          sceneBounds(), kResolution);
        double shift = 0.37 * before.texelWorldSize;
        Cascade after = fitStableCascade(camera({10 + shift, 20 - 0.5 * shift, 30 + 0.8 * shift}, 35.0, -20.0),
                                         splits[i], splits[i + 1], kSun, sceneBounds(), kResolution);
        EXPECT_EQ(before.sphereRadius, after.sphereRadius);
        // A fixed world point lands on the map at a position that differs by whole texels.
        for (const Vec3d& p : {Vec3d{0, 0, 0}, Vec3d{12.5, 3.0, -7.25}}) {
            auto a = clipOf(p, before.viewProjection), b = clipOf(p, after.viewProjection);
            for (size_t axis = 0; axis < 2; ++axis) {
                double texels = (b[axis] - a[axis]) * 0.5 * kResolution;
                EXPECT_NEAR(texels, std::round(texels), 1e-6) << "cascade " << i << " axis " << axis;
            }
        }
    }
}

TEST(ShadowCascades, TurningTheCameraKeepsTheCascadeSize) {
    auto splits = cascadeSplits(0.5, 500.0, 4, 0.75);
    for (size_t i = 0; i < 4; ++i) {
        Cascade reference = fitStableCascade(camera({10, 20, 30}, 0.0, 0.0), splits[i], splits[i + 1], kSun,
                                             sceneBounds(), kResolution);
        for (auto [yaw, pitch] : {std::pair{17.0, -5.0}, {90.0, -30.0}, {-143.0, 12.0}}) {
            Cascade turned = fitStableCascade(camera({10, 20, 30}, yaw, pitch), splits[i], splits[i + 1], kSun,
                                              sceneBounds(), kResolution);
            EXPECT_NEAR(turned.sphereRadius, reference.sphereRadius, 1e-9 * reference.sphereRadius);
            EXPECT_NEAR(turned.texelWorldSize, reference.texelWorldSize, 1e-12 * reference.texelWorldSize);
            // The map's world extent: the x scale of the projection.
            Vec3d x = {1, 0, 0};
            auto r0 = clipOf(x, reference.viewProjection), r1 = clipOf({0, 0, 0}, reference.viewProjection);
            auto t0 = clipOf(x, turned.viewProjection), t1 = clipOf({0, 0, 0}, turned.viewProjection);
            EXPECT_NEAR(std::hypot(t0[0] - t1[0], t0[1] - t1[1]), std::hypot(r0[0] - r1[0], r0[1] - r1[1]), 1e-9);
        }
    }
}

TEST(ShadowCascades, CubeFacesCoverEveryDirectionWithAGuardBand) {
    const Vec3d light = {1, 2, 3};
    const uint32_t guard = 4;
    auto faces = cubeFaceProjections(light, 0.1, 100.0, 512, guard);
    // The face of the major axis holds the direction, inside the guard band.
    const double inner = double(512 - 2 * guard) / 512.0;
    for (int i = 0; i < 2000; ++i) {
        // Directions spread over the sphere (a spherical Fibonacci set).
        double z = 1.0 - 2.0 * (i + 0.5) / 2000.0, phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
        Vec3d d = {std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z};
        size_t axis = std::abs(d[0]) >= std::abs(d[1]) && std::abs(d[0]) >= std::abs(d[2]) ? 0
                      : std::abs(d[1]) >= std::abs(d[2])                                    ? 1
                                                                                            : 2;
        size_t face = axis * 2 + (d[axis] > 0 ? 0 : 1);
        Vec3d p = {light[0] + 10 * d[0], light[1] + 10 * d[1], light[2] + 10 * d[2]};
        auto c = clipOf(p, faces[face].viewProjection);
        ASSERT_GT(c[3], 0.0);
        EXPECT_LE(std::abs(c[0] / c[3]), inner + 1e-12);
        EXPECT_LE(std::abs(c[1] / c[3]), inner + 1e-12);
        EXPECT_GT(c[2] / c[3], 0.0);
        EXPECT_LT(c[2] / c[3], 1.0);
    }
}

TEST(ShadowCascades, SpotMapHoldsItsConeWithAGuardBand) {
    const Vec3d light = {1, 2, 3}, axis = normalized({0.2, -1.0, 0.4});
    const double halfAngle = 40.0 * std::numbers::pi / 180.0;
    const uint32_t guard = 3;
    ShadowProjection spot = spotProjection(light, axis, halfAngle, 0.1, 50.0, 512, guard);
    const double inner = double(512 - 2 * guard) / 512.0;
    Matrix4d rotation = lightSpaceRotation(axis);  // rows: a basis with z along the axis
    Vec3d x = {rotation[0], rotation[4], rotation[8]}, y = {rotation[1], rotation[5], rotation[9]};
    double widest = 0.0;
    for (int i = 0; i < 360; ++i) {
        // Directions on the cone's rim: the farthest from the axis the light reaches.
        double phi = i * std::numbers::pi / 180.0;
        Vec3d d;
        for (size_t c = 0; c < 3; ++c)
            d[c] = std::cos(halfAngle) * axis[c] + std::sin(halfAngle) * (std::cos(phi) * x[c] + std::sin(phi) * y[c]);
        auto clip = clipOf({light[0] + 7 * d[0], light[1] + 7 * d[1], light[2] + 7 * d[2]}, spot.viewProjection);
        ASSERT_GT(clip[3], 0.0);
        widest = std::max({widest, std::abs(clip[0] / clip[3]), std::abs(clip[1] / clip[3])});
        EXPECT_GT(clip[2] / clip[3], 0.0);
        EXPECT_LT(clip[2] / clip[3], 1.0);
    }
    EXPECT_LE(widest, inner + 1e-12);
    EXPECT_GT(widest, 0.95 * inner) << "the map wastes texels beyond the cone";
}

Aabb boxOf(Vec3d lo, Vec3d hi) {
    Aabb b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

TEST(ShadowCascades, NearestDistanceInViewIsWhereTheFrustumFirstMeetsTheBox) {
    // Eye 2 above a floor, looking along -Z: the frustum's lower side (tan 12/50 below the axis)
    // meets the floor's top 2 / 0.24 ahead.
    ShadowedCamera cam = camera({0, 2, 0}, 0.0, 0.0);
    EXPECT_NEAR(nearestDistanceInView({boxOf({-50, -0.1, -50}, {50, 0, 50})}, cam), 2.0 / 0.24, 1e-9);
    // A wall across the view whose sides lie beyond it: its face.
    EXPECT_NEAR(nearestDistanceInView({boxOf({-100, -1, -20}, {100, 5, -10})}, cam), 10.0, 1e-9);
    // A room around the eye: the near plane.
    EXPECT_NEAR(nearestDistanceInView({boxOf({-5, -5, -5}, {5, 5, 5})}, cam), 0.5, 1e-9);
    // Behind the eye, beside the view, beyond the far plane: none of it is seen.
    EXPECT_TRUE(std::isinf(nearestDistanceInView({boxOf({-1, 0, 1}, {1, 2, 3})}, cam)));
    EXPECT_TRUE(std::isinf(nearestDistanceInView({boxOf({40, 0, -12}, {42, 2, -10})}, cam)));
    EXPECT_TRUE(std::isinf(nearestDistanceInView({boxOf({-1, 0, -700}, {1, 2, -600})}, cam)));
    EXPECT_TRUE(std::isinf(nearestDistanceInView({Aabb{}}, cam)));
}

TEST(ShadowCascades, ClipVolumeTestCullsOnlyBoxesOutsideTheView) {
    ShadowedCamera cam = camera({0, 5, 0}, 0.0, -10.0);
    Cascade cascade = fitStableCascade(cam, 0.5, 20.0, kSun, sceneBounds(), kResolution);
    Aabb inside;
    inside.extend({-1, 0, -6});
    inside.extend({1, 2, -4});
    EXPECT_FALSE(outsideClipVolume(inside, cascade.viewProjection));
    Aabb farAway;
    farAway.extend({200, 0, 200});
    farAway.extend({210, 2, 210});
    EXPECT_TRUE(outsideClipVolume(farAway, cascade.viewProjection));
    EXPECT_TRUE(outsideClipVolume(Aabb{}, cascade.viewProjection)) << "an empty box draws nothing";
}

}  // namespace
}  // namespace obscura::delegate
