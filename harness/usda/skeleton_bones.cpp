#include "harness/usda/skeleton_bones.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace obscura::usda {

namespace {

using Vec3 = std::array<double, 3>;

Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Vec3 normalized(const Vec3& v) {
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return length > 0.0 ? Vec3{v[0] / length, v[1] / length, v[2] / length} : Vec3{0, 0, 0};
}

// Row vectors: a joint's position in skeleton space is its pose's translation row.
Vec3 positionOf(const Matrix4& pose) { return {pose[12], pose[13], pose[14]}; }

}  // namespace

size_t boneCount(const Skinning& skeleton) {
    return size_t(std::count_if(skeleton.parents.begin(), skeleton.parents.end(), [](int parent) { return parent >= 0; }));
}

BoneMesh boneMesh(const Skinning& skeleton, double time, std::string* problem) {
    BoneMesh mesh;
    mesh.points = Value{"point3f", true, 3, {}, {}, false};
    mesh.faceVertexCounts = Value{"int", true, 1, {}, {}, false};
    mesh.faceVertexIndices = Value{"int", true, 1, {}, {}, false};
    const std::vector<Matrix4> pose = skeletonPose(skeleton, time, problem);
    for (size_t joint = 0; joint < pose.size(); ++joint) {
        const int parent = skeleton.parents[joint];
        if (parent < 0) continue;
        const Vec3 base = positionOf(pose[size_t(parent)]);
        const Vec3 apex = positionOf(pose[joint]);
        const Vec3 along{apex[0] - base[0], apex[1] - base[1], apex[2] - base[2]};
        const double length = std::sqrt(along[0] * along[0] + along[1] * along[1] + along[2] * along[2]);
        const Vec3 direction = normalized(along);
        // The base's axes: perpendicular to the bone, from the coordinate axis least along it, so
        // the bone's cross-section turns with it and (u, v, direction) is right-handed.
        size_t least = 0;
        for (size_t c = 1; c < 3; ++c)
            if (std::abs(direction[c]) < std::abs(direction[least])) least = c;
        Vec3 axis{0, 0, 0};
        axis[least] = 1.0;
        const Vec3 u = normalized(cross(direction, axis));
        const Vec3 v = cross(direction, u);
        const double half = kBoneHalfWidth * length;  // a bone of no length folds to its joint
        std::vector<double>& points = mesh.points.numbers.edit();
        std::vector<double>& counts = mesh.faceVertexCounts.numbers.edit();
        std::vector<double>& indices = mesh.faceVertexIndices.numbers.edit();
        const double first = double(points.size() / 3);
        // Corners counter-clockwise about the bone: (u+v), (-u+v), (-u-v), (u-v).
        for (const auto& [su, sv] : {std::pair{1.0, 1.0}, {-1.0, 1.0}, {-1.0, -1.0}, {1.0, -1.0}})
            for (size_t c = 0; c < 3; ++c) points.push_back(base[c] + half * (su * u[c] + sv * v[c]));
        points.insert(points.end(), apex.begin(), apex.end());
        // Sides wound counter-clockwise seen from outside (right-handed), then the base, seen from
        // behind the parent joint.
        for (int corner = 0; corner < 4; ++corner) {
            counts.push_back(3);
            indices.insert(indices.end(), {first + corner, first + (corner + 1) % 4, first + 4});
        }
        counts.push_back(4);
        indices.insert(indices.end(), {first + 3, first + 2, first + 1, first});
    }
    return mesh;
}

}  // namespace obscura::usda
