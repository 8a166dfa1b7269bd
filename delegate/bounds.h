// Axis-aligned bounding boxes in world or object space, and the clip-volume test that culls a box
// against a view (a shadow map's cascade or cube face, a camera).
#pragma once

#include "renderer/matrix.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace obscura::delegate {

struct Aabb {
    Vec3d min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
              std::numeric_limits<double>::infinity()};
    Vec3d max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
              -std::numeric_limits<double>::infinity()};

    bool empty() const { return min[0] > max[0] || min[1] > max[1] || min[2] > max[2]; }
    void extend(const Vec3d& p) {
        for (size_t c = 0; c < 3; ++c) {
            min[c] = std::min(min[c], p[c]);
            max[c] = std::max(max[c], p[c]);
        }
    }
    void merge(const Aabb& box) {
        if (box.empty()) return;
        extend(box.min);
        extend(box.max);
    }
    Vec3d centre() const { return {0.5 * (min[0] + max[0]), 0.5 * (min[1] + max[1]), 0.5 * (min[2] + max[2])}; }
    std::array<Vec3d, 8> corners() const {
        std::array<Vec3d, 8> c{};
        for (size_t i = 0; i < 8; ++i) c[i] = {(i & 1) ? max[0] : min[0], (i & 2) ? max[1] : min[1], (i & 4) ? max[2] : min[2]};
        return c;
    }
};

// Distance from `p` to the nearest point of the box (0 inside it).
inline double distanceTo(const Aabb& box, const Vec3d& p) {
    double squared = 0.0;
    for (size_t c = 0; c < 3; ++c) {
        double outside = std::max({box.min[c] - p[c], 0.0, p[c] - box.max[c]});
        squared += outside * outside;
    }
    return std::sqrt(squared);
}

// The box around `local` after the affine transform `m` (row-vector convention).
inline Aabb transformAabb(const Aabb& local, const Matrix4d& m) {
    Aabb world;
    if (local.empty()) return world;
    for (const Vec3d& corner : local.corners()) world.extend(transformPoint(corner, m));
    return world;
}

// Whether every point of `box` lies beyond the near plane of `viewProjection` (clip z > 0, in front
// of the eye): nothing of it is clipped there.
inline bool beyondNearPlane(const Aabb& box, const Matrix4d& viewProjection) {
    if (box.empty()) return false;
    for (const Vec3d& p : box.corners()) {
        double z = p[0] * viewProjection[2] + p[1] * viewProjection[6] + p[2] * viewProjection[10] + viewProjection[14];
        double w = p[0] * viewProjection[3] + p[1] * viewProjection[7] + p[2] * viewProjection[11] + viewProjection[15];
        if (!(z > 0.0 && w > 0.0)) return false;
    }
    return true;
}

// True when the box lies entirely outside one plane of the clip volume of `viewProjection`
// (Vulkan: -w <= x, y <= w, 0 <= z <= w). Each plane is a half-space in homogeneous
// coordinates, so the test is exact for the convex box and also holds for perspective views
// with corners behind the eye. Conservative: a box crossing a corner of the volume is kept.
inline bool outsideClipVolume(const Aabb& box, const Matrix4d& viewProjection) {
    if (box.empty()) return true;
    std::array<int, 6> outside{};  // corners outside each plane: left, right, top, bottom, near, far
    for (const Vec3d& p : box.corners()) {
        double clip[4];
        for (int j = 0; j < 4; ++j)
            clip[j] = p[0] * viewProjection[size_t(j)] + p[1] * viewProjection[size_t(4 + j)] +
                      p[2] * viewProjection[size_t(8 + j)] + viewProjection[size_t(12 + j)];
        outside[0] += clip[0] < -clip[3];
        outside[1] += clip[0] > clip[3];
        outside[2] += clip[1] < -clip[3];
        outside[3] += clip[1] > clip[3];
        outside[4] += clip[2] < 0.0;
        outside[5] += clip[2] > clip[3];
    }
    return std::any_of(outside.begin(), outside.end(), [](int n) { return n == 8; });
}

}  // namespace obscura::delegate
