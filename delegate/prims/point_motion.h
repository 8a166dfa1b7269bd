// Points that move within the camera's shutter, as USD computes them
// (UsdGeomPointBased::ComputePointsAtTime, UsdGeomPointInstancer::ComputeInstanceTransformsAtTime):
// with `velocities` (and `accelerations`) of one vector per point, a point at dt seconds from the
// frame is p + dt (v + dt a / 2), not an interpolation between time samples (which particles that
// are born and die between samples cannot have); without them, the host's interpolated value, and
// where that has another count than the frame's, the frame's own.
#pragma once

#include <optional>
#include <vector>

namespace obscura::delegate {

struct PointMotion {
    std::vector<float> velocities;     // xyz per point, scene units per second
    std::vector<float> accelerations;  // xyz per point, or empty
};

// The motion `velocities` and `accelerations` give `count` points, or nullopt when velocities do not
// hold one vector per point (accelerations without one per point are left out).
std::optional<PointMotion> pointMotion(const std::optional<std::vector<float>>& velocities,
                                       const std::optional<std::vector<float>>& accelerations, size_t count);

// `points` (xyz) moved for `seconds`.
std::vector<float> movePoints(const std::vector<float>& points, const PointMotion& motion, double seconds);

// A time-sampled array at another time, or the frame's where the host has none or one of another
// size there (USD's fallback to the base time's data).
std::vector<float> sampledOrFrame(const std::optional<std::vector<float>>& sampled, const std::vector<float>& frame);

// Seconds from the frame's time to `time` (both in time codes).
inline double secondsBetween(double frameTime, double time, double timeCodesPerSecond) {
    return (time - frameTime) / timeCodesPerSecond;
}

}  // namespace obscura::delegate
