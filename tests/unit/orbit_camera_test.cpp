// The viewer's free camera (harness/view/orbit_camera.h) against the geometry of a pinhole camera:
// a pan keeps the point under the cursor under it, a window-wide drag orbits half a circle, the
// horizon stays level, framing fits a sphere in the view cone, and looking through a camera's
// transform gives that transform back.
#include "harness/view/orbit_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace obscura::harness::view {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTolerance = 1e-9;

Vector3 row(const Matrix4& m, int i) { return {m[4 * i], m[4 * i + 1], m[4 * i + 2]}; }
Vector3 eyeOf(const OrbitCamera& camera) { return row(camera.matrix(), 3); }
Vector3 minus(const Vector3& a, const Vector3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Vector3& v) { return std::sqrt(dot(v, v)); }

void expectNear(const Vector3& actual, const Vector3& expected, double tolerance = kTolerance) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

// Where a world point lands on the image, in pixels from its centre (x right, y down), for a
// pinhole camera of this vertical field of view over `height` pixels; looking down -z.
std::array<double, 2> project(const OrbitCamera& camera, const Vector3& point, double verticalFov, double height) {
    const Matrix4 m = camera.matrix();
    const Vector3 d = minus(point, row(m, 3));
    const double x = dot(d, row(m, 0)), y = dot(d, row(m, 1)), z = dot(d, row(m, 2));
    const double pixelsPerUnit = 0.5 * height / std::tan(0.5 * verticalFov);
    return {pixelsPerUnit * x / -z, -pixelsPerUnit * y / -z};
}

TEST(OrbitCamera, MatrixIsOrthonormalWithItsEyeBehindTheTarget) {
    for (const char* up : {"Y", "Z"}) {
        OrbitCamera camera(up);
        camera.orbit(37.0, -21.0, 100.0);
        const Matrix4 m = camera.matrix();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) EXPECT_NEAR(dot(row(m, i), row(m, j)), i == j ? 1.0 : 0.0, kTolerance);
        // Rows x, y, z: a right-handed frame looking down -z at the target.
        const Vector3 x = row(m, 0), y = row(m, 1), z = row(m, 2);
        expectNear({x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]}, z);
        const Vector3 toEye = minus(eyeOf(camera), camera.target());
        EXPECT_NEAR(length(toEye), camera.distance(), kTolerance);
        expectNear({toEye[0] / camera.distance(), toEye[1] / camera.distance(), toEye[2] / camera.distance()}, z);
    }
}

TEST(OrbitCamera, StartsLookingAlongTheStagesHorizonWithItsUpAxisUp) {
    OrbitCamera yUp("Y");
    expectNear(row(yUp.matrix(), 1), {0, 1, 0});
    expectNear(row(yUp.matrix(), 2), {0, 0, 1});  // USD's default camera: looking down -Z
    OrbitCamera zUp("Z");
    expectNear(row(zUp.matrix(), 1), {0, 0, 1});
    expectNear(row(zUp.matrix(), 2), {0, -1, 0});  // looking along +Y
}

TEST(OrbitCamera, AWindowWideDragOrbitsHalfACircleAboutTheTarget) {
    OrbitCamera camera("Y");
    const double width = 640.0;
    const Vector3 before = minus(eyeOf(camera), camera.target());
    camera.orbit(width, 0.0, width);
    const Vector3 after = minus(eyeOf(camera), camera.target());
    expectNear(after, {-before[0], before[1], -before[2]});
    camera.orbit(width / 2, 0.0, width);  // a quarter turn more
    EXPECT_NEAR(dot(minus(eyeOf(camera), camera.target()), before), 0.0, kTolerance);
}

TEST(OrbitCamera, TheHorizonStaysLevelAndThePoleIsNeverReached) {
    for (const char* upAxis : {"Y", "Z"}) {
        OrbitCamera camera(upAxis);
        const Vector3 up = std::string(upAxis) == "Z" ? Vector3{0, 0, 1} : Vector3{0, 1, 0};
        camera.orbit(123.0, 45.0, 400.0);
        EXPECT_NEAR(dot(row(camera.matrix(), 0), up), 0.0, kTolerance);  // a turntable: x stays horizontal
        camera.orbit(0.0, 10000.0, 400.0);  // far past the pole: stops 1 degree short of it
        const Vector3 toEye = minus(eyeOf(camera), camera.target());
        EXPECT_NEAR(std::asin(dot(toEye, up) / camera.distance()), 89.0 * kPi / 180.0, 1e-12);
        camera.orbit(0.0, -20000.0, 400.0);
        EXPECT_NEAR(std::asin(dot(minus(eyeOf(camera), camera.target()), up) / camera.distance()), -89.0 * kPi / 180.0,
                    1e-12);
    }
}

TEST(OrbitCamera, PanKeepsThePointUnderTheCursorUnderIt) {
    const double fov = 0.8, height = 480.0;
    for (const char* upAxis : {"Y", "Z"}) {
        OrbitCamera camera(upAxis);
        camera.orbit(50.0, 30.0, 640.0);
        const Vector3 grabbed = camera.target();  // under the cursor at the image's centre
        const double dx = 40.0, dy = -25.0;
        camera.pan(dx, dy, height, fov);
        const auto pixel = project(camera, grabbed, fov, height);
        EXPECT_NEAR(pixel[0], dx, 1e-9);
        EXPECT_NEAR(pixel[1], dy, 1e-9);
        EXPECT_NEAR(camera.distance(), 10.0, kTolerance);  // a pan does not move towards the scene
    }
}

TEST(OrbitCamera, DollyScalesTheDistanceByAFactorPerStep) {
    OrbitCamera camera("Y");
    const Vector3 target = camera.target();
    const Vector3 axis = row(camera.matrix(), 2);
    camera.dolly(3.0);
    EXPECT_NEAR(camera.distance(), 10.0 * std::pow(0.9, 3.0), kTolerance);
    expectNear(camera.target(), target);
    expectNear(row(camera.matrix(), 2), axis);
    camera.dolly(-3.0);
    EXPECT_NEAR(camera.distance(), 10.0, kTolerance);
    camera.dolly(1e6);  // never onto the target
    EXPECT_GT(camera.distance(), 0.0);
}

TEST(OrbitCamera, FlyMovesEyeAndTargetTogetherInTheCamerasFrame) {
    OrbitCamera camera("Z");
    camera.orbit(80.0, 20.0, 640.0);
    const Matrix4 before = camera.matrix();
    const Vector3 target = camera.target();
    camera.fly({0, 0, -1}, 2.5);  // forwards
    const Vector3 forward = row(before, 2);
    expectNear(camera.target(), {target[0] - 2.5 * forward[0], target[1] - 2.5 * forward[1], target[2] - 2.5 * forward[2]});
    expectNear(minus(eyeOf(camera), row(before, 3)), minus(camera.target(), target));
    for (int i = 0; i < 3; ++i) expectNear(row(camera.matrix(), i), row(before, i));
    camera.fly({1, 0, 0}, 1.0);  // right
    expectNear(minus(camera.target(), target), {-2.5 * forward[0] + before[0], -2.5 * forward[1] + before[1],
                                                -2.5 * forward[2] + before[2]});
}

TEST(OrbitCamera, FrameFitsTheSphereInTheNarrowerFieldOfView) {
    OrbitCamera camera("Y");
    const Vector3 centre{1.0, -2.0, 3.0};
    const double radius = 4.0, fov = 0.6;
    camera.frame(centre, radius, fov);
    expectNear(camera.target(), centre);
    // The sphere touches the view cone: the angle to its silhouette is half the field of view.
    EXPECT_NEAR(std::asin(radius / length(minus(eyeOf(camera), centre))), 0.5 * fov, kTolerance);
}

TEST(OrbitCamera, LookingThroughACameraGivesItsTransformBack) {
    for (const char* upAxis : {"Y", "Z"}) {
        OrbitCamera scene(upAxis);
        scene.frame({2.0, 1.0, -1.0}, 3.0, 0.7);
        scene.orbit(-150.0, 60.0, 500.0);
        OrbitCamera free(upAxis);
        free.lookThrough(scene.matrix(), scene.distance());
        const Matrix4 a = scene.matrix(), b = free.matrix();
        for (int i = 0; i < 16; ++i) EXPECT_NEAR(b[i], a[i], 1e-9) << upAxis << " element " << i;
        expectNear(free.target(), scene.target(), 1e-9);
    }
}

}  // namespace
}  // namespace obscura::harness::view
