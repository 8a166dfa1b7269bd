#include "delegate/prims/point_motion.h"

namespace obscura::delegate {

std::optional<PointMotion> pointMotion(const std::optional<std::vector<float>>& velocities,
                                       const std::optional<std::vector<float>>& accelerations, size_t count) {
    if (!velocities || velocities->size() != 3 * count) return std::nullopt;
    PointMotion motion{*velocities, {}};
    if (accelerations && accelerations->size() == 3 * count) motion.accelerations = *accelerations;
    return motion;
}

std::vector<float> movePoints(const std::vector<float>& points, const PointMotion& motion, double seconds) {
    std::vector<float> moved(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        double velocity = motion.velocities[i];
        if (!motion.accelerations.empty()) velocity += 0.5 * seconds * motion.accelerations[i];
        moved[i] = float(points[i] + seconds * velocity);
    }
    return moved;
}

std::vector<float> sampledOrFrame(const std::optional<std::vector<float>>& sampled, const std::vector<float>& frame) {
    return sampled && sampled->size() == frame.size() ? *sampled : frame;
}

}  // namespace obscura::delegate
