// The projections of shadow maps, computed on the CPU each frame: cascades of a distant light
// (cascaded shadow maps, stable under camera motion) and the six cube faces of a sphere light.
// Pure math in the row-vector convention of renderer/matrix.h; unit-tested without a GPU.
#pragma once

#include "delegate/bounds.h"
#include "renderer/matrix.h"

#include <array>
#include <cstdint>
#include <vector>

namespace obscura::delegate {

// View distances (along the camera's view axis) that bound `count` cascades between `near` and
// `far`: count + 1 values, near first, far last. The practical split scheme (Zhang et al. 2006,
// "Parallel-split shadow maps"): each split blends the logarithmic split near (far/near)^(i/n),
// which keeps the texel-to-pixel ratio even across cascades, with the uniform split
// near + (far-near) i/n, which keeps near cascades from becoming tiny; `lambda` weights the log.
std::vector<double> cascadeSplits(double near, double far, uint32_t count, double lambda);

// The camera whose view a distant light's cascades cover.
struct ShadowedCamera {
    Matrix4d view;        // world -> view (the camera looks down -Z)
    Matrix4d projection;  // view -> clip (Vulkan clip space), perspective or orthographic
};

// The eight world-space corners of the camera frustum between view distances `near` and `far`:
// near rectangle first, in the order (-x -y, +x -y, -x +y, +x +y) of normalized device coordinates.
std::array<Vec3d, 8> frustumSliceCorners(const ShadowedCamera& camera, double near, double far);

// The smallest view distance of the parts of `boxes` that lie inside the camera's frustum (its
// clipping range included), +infinity where none does. The minimum of a linear function over a
// box's convex intersection with the frustum lies on one of its vertices: the box's faces clipped
// to the frustum's six planes, or a corner of the frustum's near rectangle inside the box.
double nearestDistanceInView(const std::vector<Aabb>& boxes, const ShadowedCamera& camera);

// World -> light space rotation for a light travelling along `direction`: x and y span the shadow
// map, z increases along the direction. Depends only on the direction, so a light's shadow-map
// texels keep their orientation while the camera moves.
Matrix4d lightSpaceRotation(const Vec3d& direction);

struct ShadowProjection {
    Matrix4d viewProjection;  // world -> clip of the shadow map (Vulkan clip space)
    // World size of one shadow-map texel: for orthographic views the texel's extent, for
    // perspective views its extent at distance 1 from the light (scaled by distance in the lookup).
    double texelWorldSize = 0.0;
};

struct Cascade : ShadowProjection {
    Vec3d sphereCenter{};  // bounding sphere of the frustum slice the cascade covers
    double sphereRadius = 0.0;
    double depthSpan = 0.0;  // world distance along the light between depths 0 and 1 of the map
};

// One cascade of a distant light travelling along `lightDirection`, covering the camera's
// frustum between view distances `sliceNear` and `sliceFar` on a `resolution`² shadow map.
// Stable cascades (Valient 2008, "Stable rendering of cascaded shadow maps", ShaderX6):
// * the map covers the slice's bounding sphere, whose radius depends only on the slice's shape in
//   view space, so turning the camera never changes the projection's size;
// * the projection's origin is snapped to whole texels in light space, so moving the camera
//   moves the map by whole texels and shadow edges do not crawl.
// Depth spans `casters` along the light (every caster in front of the slice lands in the map).
Cascade fitStableCascade(const ShadowedCamera& camera, double sliceNear, double sliceFar, const Vec3d& lightDirection,
                         const Aabb& casters, uint32_t resolution);

// The six 90-degree faces of an omnidirectional (cube) shadow map around `position`, in the order
// +X, -X, +Y, -Y, +Z, -Z of the direction from the light (the lookup picks the face by the major
// axis). Each face widens its field of view so that `guardTexels` texels on every side lie
// beyond 90 degrees: a filter kernel near a face's edge reads valid depths.
std::array<ShadowProjection, 6> cubeFaceProjections(const Vec3d& position, double near, double far,
                                                     uint32_t resolution, uint32_t guardTexels);

// One perspective map looking along `axis` from `position` whose field of view holds the cone of
// half-angle `halfAngle` (radians, below 90 degrees) with `guardTexels` texels to spare on every side.
ShadowProjection spotProjection(const Vec3d& position, const Vec3d& axis, double halfAngle, double near, double far,
                                uint32_t resolution, uint32_t guardTexels);

}  // namespace obscura::delegate
