#include "harness/view/orbit_camera.h"

#include <algorithm>
#include <cmath>

namespace obscura::harness::view {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Short of the poles, where a turntable's frame flips.
constexpr double kMaxPitch = 89.0 * kPi / 180.0;

Vector3 add(const Vector3& a, const Vector3& b, double s = 1.0) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }
double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vector3 cross(const Vector3& a, const Vector3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vector3 normalized(const Vector3& v) {
    double n = std::sqrt(dot(v, v));
    return n > 0 ? Vector3{v[0] / n, v[1] / n, v[2] / n} : v;
}

}  // namespace

OrbitCamera::OrbitCamera(const std::string& upAxis) {
    if (upAxis == "Z") up_ = {0, 0, 1}, forward0_ = {0, -1, 0}, right0_ = {1, 0, 0};
    else up_ = {0, 1, 0}, forward0_ = {0, 0, 1}, right0_ = {1, 0, 0};
}

Vector3 OrbitCamera::direction() const {
    Vector3 horizontal = add(Vector3{}, right0_, std::sin(yaw_));
    horizontal = add(horizontal, forward0_, std::cos(yaw_));
    Vector3 d{};
    d = add(d, horizontal, std::cos(pitch_));
    return add(d, up_, std::sin(pitch_));
}

void OrbitCamera::orbit(double dx, double dy, double viewportWidth) {
    const double radiansPerPixel = kPi / std::max(viewportWidth, 1.0);
    yaw_ -= dx * radiansPerPixel;
    pitch_ = std::clamp(pitch_ + dy * radiansPerPixel, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(double dx, double dy, double viewportHeight, double verticalFov) {
    // Scene units per pixel at the target's distance.
    const double scale = 2.0 * distance_ * std::tan(0.5 * verticalFov) / std::max(viewportHeight, 1.0);
    const Matrix4 m = matrix();
    const Vector3 x{m[0], m[1], m[2]}, y{m[4], m[5], m[6]};
    target_ = add(target_, x, -dx * scale);
    target_ = add(target_, y, dy * scale);
}

void OrbitCamera::dolly(double steps) { distance_ = std::max(distance_ * std::pow(0.9, steps), 1e-6); }

void OrbitCamera::fly(const Vector3& d, double distance) {
    const Matrix4 m = matrix();
    Vector3 move = add(add(add(Vector3{}, Vector3{m[0], m[1], m[2]}, d[0]), Vector3{m[4], m[5], m[6]}, d[1]),
                       Vector3{m[8], m[9], m[10]}, d[2]);
    target_ = add(target_, normalized(move), distance);
}

void OrbitCamera::frame(const Vector3& centre, double radius, double narrowFov) {
    target_ = centre;
    distance_ = radius / std::sin(0.5 * narrowFov);
}

void OrbitCamera::lookThrough(const Matrix4& m, double focus) {
    const Vector3 eye{m[12], m[13], m[14]};
    const Vector3 back = normalized({m[8], m[9], m[10]});
    distance_ = std::max(focus, 1e-6);
    target_ = add(eye, back, -distance_);
    pitch_ = std::asin(std::clamp(dot(back, up_), -std::sin(kMaxPitch), std::sin(kMaxPitch)));
    yaw_ = std::atan2(dot(back, right0_), dot(back, forward0_));
}

Matrix4 OrbitCamera::matrix() const {
    const Vector3 z = normalized(direction());
    const Vector3 x = normalized(cross(up_, z));
    const Vector3 y = cross(z, x);
    const Vector3 eye = add(target_, z, distance_);
    return {x[0], x[1], x[2], 0, y[0], y[1], y[2], 0, z[0], z[1], z[2], 0, eye[0], eye[1], eye[2], 1};
}

}  // namespace obscura::harness::view
