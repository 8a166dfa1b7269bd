// UsdGeom's implicit surfaces (Cube, Sphere, Cylinder, Cone, Capsule and their _1 variants, Plane)
// turned into the polygons the mesh path draws, at a density chosen from their size on screen.
// Pure CPU code: no Vulkan, unit-tested on its own.
//
// Storm tessellates every implicit surface once, at a fixed density (GeomUtil's mesh
// generators), so a sphere filling the screen shows its facets and a distant one wastes
// triangles. Here the curved surfaces are cut into a number of segments around their axis that
// keeps the chord's distance from the true silhouette under a fraction of a pixel; the count is
// quantised to powers of two (levels) and changes only when the wanted level leaves a band around
// the current one, so a slowly moving camera does not make the silhouette flicker between counts.
#pragma once

#include "delegate/bounds.h"
#include "delegate/mesh_builder.h"

#include <string>

namespace obscura::delegate {

enum class ImplicitKind { Cube, Sphere, Frustum, Capsule, Plane };

// The shape's parameters in the schema's units (scene units). A cylinder, a cone and a
// Cylinder_1 are all frusta (radiusTop 0 is a cone); a Capsule and a Capsule_1 are capsules.
struct ImplicitShape {
    ImplicitKind kind = ImplicitKind::Sphere;
    double size = 2.0;                              // cube edge
    double radiusBottom = 1.0, radiusTop = 1.0;     // sphere: radiusBottom
    double height = 2.0;
    double width = 2.0, length = 2.0;               // plane
    int axis = 2;                                   // 0 X, 1 Y, 2 Z
};

// Why the parameters describe no surface ("radius is -1; it must be positive"), or "".
std::string implicitShapeProblem(const ImplicitShape& shape);

// The shape's object-space bounds (UsdGeom's ComputeExtent for it).
Aabb implicitShapeBounds(const ImplicitShape& shape);

// The largest radius of curvature around the axis that tessellation must follow, in object
// space; 0 for the flat shapes (cube, plane), whose polygons are exact at any size.
double implicitCurvatureRadius(const ImplicitShape& shape);

// Segments around the axis at a tessellation level: 8 x 2^level.
constexpr int kImplicitMinLevel = 0;
constexpr int kImplicitMaxLevel = 6;  // 512 segments: a 0.1 px chord error up to a 5000 px radius
int implicitSegments(int level);

// The level whose chords stay within `maxErrorPixels` of a circle `radiusPixels` across on screen,
// as a real number (the sagitta of N chords on radius R is R (1 - cos(pi / N)) ~ R pi^2 / (2 N^2)),
// not yet clamped or rounded.
double wantedImplicitLevel(double radiusPixels, double maxErrorPixels);

// The level (2^level steps along a parametric span) whose chords stay within `maxErrorPixels` of a
// curve whose second derivative over the span's parameter, normalised to [0, 1], is at most
// `bendPixels` on screen: a step of 1/n departs from its chord by at most bendPixels / (8 n^2).
// Not yet clamped or rounded; 0 where one step is close enough.
double wantedStepLevel(double bendPixels, double maxErrorPixels);

// The level to draw with, given the level wanted now and the one drawn so far (-1: none yet):
// the current level stays while the wanted one is within 0.75 of it (hysteresis), otherwise the
// nearest level, clamped to [kImplicitMinLevel, kImplicitMaxLevel].
int chooseImplicitLevel(double wantedLevel, int currentLevel);

// The shape's polygons with `segments` around the axis: points, faces, face-varying normals
// (smooth on curved parts, flat on caps and cube faces) and face-varying st (s around the axis
// from +X, t along it from its bottom, as RenderMan's quadrics parametrise them; each cube face
// and the plane span [0, 1]^2). Front faces wind counter-clockwise seen from outside
// (rightHanded); a leftHanded shape is turned inside out like a mesh with those points would be.
MeshInput tessellateImplicitShape(const ImplicitShape& shape, int segments, bool leftHanded);

}  // namespace obscura::delegate
