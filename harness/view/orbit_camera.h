// The viewer's free camera: orbit about a target, pan, dolly and fly, as usdview's and DCC
// viewports' cameras move, expressed as the camera prim's transform (USD's GfMatrix4d convention:
// rows are the camera's x, y, z axes and its position; it looks down -z).
#pragma once

#include <array>
#include <string>

namespace obscura::harness::view {

using Matrix4 = std::array<double, 16>;
using Vector3 = std::array<double, 3>;

class OrbitCamera {
public:
    // `upAxis`: the stage's "Y" or "Z".
    explicit OrbitCamera(const std::string& upAxis = "Y");

    // Turntable orbit: `dx`, `dy` pixels of mouse motion; a full window width turns half a circle.
    void orbit(double dx, double dy, double viewportWidth);
    // Moves the target with the image: the point under the cursor stays under it.
    void pan(double dx, double dy, double viewportHeight, double verticalFov);
    // Towards (positive) or away from the target, by a factor per step (a scroll notch).
    void dolly(double steps);
    // Moves eye and target together, in the camera's frame (x right, y up, z backwards), by
    // `distance` scene units.
    void fly(const Vector3& direction, double distance);
    // Looks at a sphere so that it fills the narrower field of view.
    void frame(const Vector3& centre, double radius, double narrowFov);
    // Takes the place and direction of a camera transform, its target `focus` ahead.
    void lookThrough(const Matrix4& cameraToWorld, double focus);

    Matrix4 matrix() const;
    const Vector3& target() const { return target_; }
    double distance() const { return distance_; }

private:
    Vector3 direction() const;  // from the target to the eye
    Vector3 up_, forward0_, right0_;  // the stage's up and a horizontal frame (yaw 0 looks down -forward0)
    Vector3 target_{};
    double distance_ = 10.0;
    double yaw_ = 0.0, pitch_ = 0.0;  // radians
};

}  // namespace obscura::harness::view
