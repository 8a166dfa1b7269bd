#include "delegate/shadow_cascades.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace obscura::delegate {
namespace {

// Row-vector matrix whose columns are the basis vectors: p * M = (p.x', p.y', p.z').
Matrix4d basisMatrix(const Vec3d& x, const Vec3d& y, const Vec3d& z) {
    return {x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, 0, 0, 0, 1};
}

// The frustum slice in view space: corners between view distances near and far.
std::array<Vec3d, 8> viewSpaceSliceCorners(const Matrix4d& projection, double near, double far) {
    Matrix4d inverse = kIdentity;
    invert(projection, inverse);
    std::array<Vec3d, 8> corners{};
    for (size_t i = 0; i < 4; ++i) {
        double x = (i & 1) ? 1.0 : -1.0, y = (i & 2) ? 1.0 : -1.0;
        // The edge of the frustum through this corner, from its near-plane point to its far-plane
        // point; a straight line in view space for perspective and orthographic projections.
        Vec3d a = transformPoint({x, y, 0.0}, inverse), b = transformPoint({x, y, 1.0}, inverse);
        double da = -a[2], db = -b[2];  // view distances (the camera looks down -Z)
        corners[i] = add(a, scale(sub(b, a), (near - da) / (db - da)));
        corners[i + 4] = add(a, scale(sub(b, a), (far - da) / (db - da)));
    }
    return corners;
}

double farthestCorner(const std::array<Vec3d, 8>& corners, const Vec3d& center) {
    double r2 = 0.0;
    for (const Vec3d& c : corners) r2 = std::max(r2, dot(sub(c, center), sub(c, center)));
    return std::sqrt(r2);
}

// A square perspective view from `position` along the unit `forward` (with `up` perpendicular to
// it) whose inner resolution - 2 guard texels span the half-angle whose tangent is `tanInner`.
ShadowProjection perspectiveView(const Vec3d& position, const Vec3d& forward, const Vec3d& up, double tanInner,
                                 double near, double far, uint32_t resolution, uint32_t guardTexels) {
    double tanHalf = tanInner * double(resolution) / double(resolution - 2 * guardTexels);
    // Perspective with the distance along the view axis as w; depth 0 at near, 1 at far.
    Matrix4d perspective{};
    perspective[0] = 1.0 / tanHalf;
    perspective[5] = 1.0 / tanHalf;
    perspective[10] = far / (far - near);
    perspective[11] = 1.0;
    perspective[14] = -near * far / (far - near);
    Matrix4d view = basisMatrix(cross(up, forward), up, forward);
    Vec3d t = transformPoint(position, view);
    view[12] = -t[0];
    view[13] = -t[1];
    view[14] = -t[2];
    return {multiply(view, perspective), 2.0 * tanHalf / double(resolution)};
}

// The six half-spaces of Vulkan clip space (w ± x, w ± y, z, w - z not negative), each as a
// linear function of world position: coefficients of x, y, z and the constant.
std::array<std::array<double, 4>, 6> clipHalfSpaces(const Matrix4d& viewProjection) {
    auto column = [&](int j) {
        return std::array<double, 4>{viewProjection[size_t(j)], viewProjection[size_t(4 + j)],
                                     viewProjection[size_t(8 + j)], viewProjection[size_t(12 + j)]};
    };
    const auto x = column(0), y = column(1), z = column(2), w = column(3);
    std::array<std::array<double, 4>, 6> planes{};
    for (size_t k = 0; k < 4; ++k) {
        planes[0][k] = w[k] + x[k];
        planes[1][k] = w[k] - x[k];
        planes[2][k] = w[k] + y[k];
        planes[3][k] = w[k] - y[k];
        planes[4][k] = z[k];
        planes[5][k] = w[k] - z[k];
    }
    return planes;
}

double evaluate(const std::array<double, 4>& plane, const Vec3d& p) {
    return plane[0] * p[0] + plane[1] * p[1] + plane[2] * p[2] + plane[3];
}

// A box's face clipped by the frustum: a quad cut by six planes keeps at most 4 + 6 corners.
struct ClippedFace {
    std::array<Vec3d, 10> points{};
    size_t count = 0;
};

// Sutherland-Hodgman: the part of the convex polygon on the plane's non-negative side.
ClippedFace clipPolygon(const ClippedFace& polygon, const std::array<double, 4>& plane) {
    ClippedFace kept;
    for (size_t i = 0; i < polygon.count; ++i) {
        const Vec3d& a = polygon.points[i];
        const Vec3d& b = polygon.points[(i + 1) % polygon.count];
        const double da = evaluate(plane, a), db = evaluate(plane, b);
        if (da >= 0.0) kept.points[kept.count++] = a;
        if ((da >= 0.0) != (db >= 0.0)) kept.points[kept.count++] = add(a, scale(sub(b, a), da / (da - db)));
    }
    return kept;
}

}  // namespace

double nearestDistanceInView(const std::vector<Aabb>& boxes, const ShadowedCamera& camera) {
    const Matrix4d viewProjection = multiply(camera.view, camera.projection);
    const auto planes = clipHalfSpaces(viewProjection);
    Matrix4d inverse = kIdentity;
    invert(viewProjection, inverse);
    std::array<Vec3d, 4> nearCorners{};
    for (size_t i = 0; i < 4; ++i) nearCorners[i] = transformPoint({(i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, 0.0}, inverse);
    const auto distance = [&](const Vec3d& p) { return -transformPoint(p, camera.view)[2]; };
    // Corner indices of Aabb::corners() (bit 0: x, bit 1: y, bit 2: z), face by face.
    constexpr size_t kFaces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    double nearest = std::numeric_limits<double>::infinity();
    for (const Aabb& box : boxes) {
        if (box.empty()) continue;
        const std::array<Vec3d, 8> corners = box.corners();
        // Distance is linear: no point of the box, seen or not, is nearer than its nearest corner.
        double nearestCorner = std::numeric_limits<double>::infinity();
        for (const Vec3d& c : corners) nearestCorner = std::min(nearestCorner, distance(c));
        if (nearestCorner >= nearest) continue;
        for (const auto& face : kFaces) {
            ClippedFace polygon{{corners[face[0]], corners[face[1]], corners[face[2]], corners[face[3]]}, 4};
            for (const auto& plane : planes) {
                polygon = clipPolygon(polygon, plane);
                if (polygon.count == 0) break;
            }
            for (size_t i = 0; i < polygon.count; ++i) nearest = std::min(nearest, distance(polygon.points[i]));
        }
        for (const Vec3d& corner : nearCorners) {
            bool inside = true;
            for (size_t c = 0; c < 3; ++c) inside = inside && corner[c] >= box.min[c] && corner[c] <= box.max[c];
            if (inside) nearest = std::min(nearest, distance(corner));
        }
    }
    return nearest;
}

std::vector<double> cascadeSplits(double near, double far, uint32_t count, double lambda) {
    std::vector<double> splits(count + 1);
    for (uint32_t i = 0; i <= count; ++i) {
        double t = double(i) / double(count);
        double logarithmic = near * std::pow(far / near, t);
        double uniform = near + (far - near) * t;
        splits[i] = lambda * logarithmic + (1.0 - lambda) * uniform;
    }
    // Exact ends: the first cascade starts at the near plane, the last one ends at far.
    splits.front() = near;
    splits.back() = far;
    return splits;
}

std::array<Vec3d, 8> frustumSliceCorners(const ShadowedCamera& camera, double near, double far) {
    Matrix4d viewToWorld = kIdentity;
    invert(camera.view, viewToWorld);
    std::array<Vec3d, 8> corners = viewSpaceSliceCorners(camera.projection, near, far);
    for (Vec3d& c : corners) c = transformPoint(c, viewToWorld);
    return corners;
}

Matrix4d lightSpaceRotation(const Vec3d& direction) {
    Vec3d z = normalized(direction);
    // Any up vector not parallel to the direction will do; it must depend on the direction alone.
    Vec3d up = std::abs(z[1]) < 0.99 ? Vec3d{0, 1, 0} : Vec3d{1, 0, 0};
    Vec3d x = normalized(cross(up, z));
    Vec3d y = cross(z, x);
    return basisMatrix(x, y, z);
}

Cascade fitStableCascade(const ShadowedCamera& camera, double sliceNear, double sliceFar, const Vec3d& lightDirection,
                         const Aabb& casters, uint32_t resolution) {
    // The bounding sphere is fitted in view space, where the slice's shape does not depend on the
    // camera's orientation or position: its radius is the same every frame. The centre lies on
    // the segment joining the centres of the slice's near and far rectangles; the farthest-corner
    // distance is convex along it, so a ternary search finds the smallest enclosing sphere of
    // that family (for a symmetric frustum the minimal sphere, (n+f)(1+k²)/2 deep, clamped to f).
    std::array<Vec3d, 8> corners = viewSpaceSliceCorners(camera.projection, sliceNear, sliceFar);
    Vec3d nearCenter = scale(add(add(corners[0], corners[1]), add(corners[2], corners[3])), 0.25);
    Vec3d farCenter = scale(add(add(corners[4], corners[5]), add(corners[6], corners[7])), 0.25);
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 100; ++i) {
        double a = lo + (hi - lo) / 3.0, b = hi - (hi - lo) / 3.0;
        double ra = farthestCorner(corners, add(nearCenter, scale(sub(farCenter, nearCenter), a)));
        double rb = farthestCorner(corners, add(nearCenter, scale(sub(farCenter, nearCenter), b)));
        if (ra < rb) hi = b;
        else lo = a;
    }
    Vec3d viewCenter = add(nearCenter, scale(sub(farCenter, nearCenter), 0.5 * (lo + hi)));
    double radius = farthestCorner(corners, viewCenter);

    Matrix4d viewToWorld = kIdentity;
    invert(camera.view, viewToWorld);
    Cascade cascade;
    cascade.sphereCenter = transformPoint(viewCenter, viewToWorld);
    cascade.sphereRadius = radius;

    // The sphere's diameter spans resolution - 2 texels: snapping the origin down to a whole
    // texel moves it by less than one texel, and the sphere stays inside the map.
    double texel = 2.0 * radius / double(resolution - 2);
    double halfExtent = 0.5 * texel * double(resolution);
    Matrix4d rotation = lightSpaceRotation(lightDirection);
    Vec3d center = transformPoint(cascade.sphereCenter, rotation);
    double originX = std::floor(center[0] / texel) * texel;
    double originY = std::floor(center[1] / texel) * texel;

    // Depth covers every caster along the light and the sphere itself.
    double zMin = center[2] - radius, zMax = center[2] + radius;
    if (!casters.empty())
        for (const Vec3d& c : casters.corners()) {
            double z = transformPoint(c, rotation)[2];
            zMin = std::min(zMin, z);
            zMax = std::max(zMax, z);
        }
    Matrix4d ortho = kIdentity;
    ortho[0] = 1.0 / halfExtent;
    ortho[5] = 1.0 / halfExtent;
    ortho[10] = 1.0 / (zMax - zMin);
    ortho[12] = -originX / halfExtent;
    ortho[13] = -originY / halfExtent;
    ortho[14] = -zMin / (zMax - zMin);
    cascade.viewProjection = multiply(rotation, ortho);
    cascade.texelWorldSize = texel;
    cascade.depthSpan = zMax - zMin;
    return cascade;
}

std::array<ShadowProjection, 6> cubeFaceProjections(const Vec3d& position, double near, double far,
                                                     uint32_t resolution, uint32_t guardTexels) {
    const std::array<Vec3d, 6> forward = {Vec3d{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const std::array<Vec3d, 6> up = {Vec3d{0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};
    std::array<ShadowProjection, 6> faces{};
    for (size_t f = 0; f < 6; ++f)
        faces[f] = perspectiveView(position, forward[f], up[f], 1.0, near, far, resolution, guardTexels);
    return faces;
}

ShadowProjection spotProjection(const Vec3d& position, const Vec3d& axis, double halfAngle, double near, double far,
                                uint32_t resolution, uint32_t guardTexels) {
    Vec3d forward = normalized(axis);
    Vec3d reference = std::abs(forward[1]) < 0.99 ? Vec3d{0, 1, 0} : Vec3d{1, 0, 0};
    Vec3d up = normalized(cross(forward, cross(reference, forward)));
    return perspectiveView(position, forward, up, std::tan(halfAngle), near, far, resolution, guardTexels);
}

}  // namespace obscura::delegate
