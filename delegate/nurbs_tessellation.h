// UsdGeomNurbsPatch turned into the polygons the mesh path draws: the rational B-spline surface
// itself, evaluated on a grid of steps per knot span, not its control hull (which is what Storm
// draws). Pure CPU code: no Vulkan, unit-tested on its own.
//
// The encoding is the schema's (after RiNuPatch): uVertexCount x vVertexCount control points with
// u varying fastest, knot vectors of vertexCount + order values, optional weights (rational) and
// parameter ranges. Basis functions and their derivatives by the Cox-de Boor recursion (Piegl and
// Tiller, "The NURBS Book", 2nd ed., eq. 2.5 and 2.7); rational derivatives by eq. 4.8.
// Trim curves are not applied (nor by Storm): the untrimmed surface is drawn.
#pragma once

#include "delegate/mesh_builder.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace obscura::delegate {

// One parametric direction of a patch.
struct NurbsDirection {
    int vertexCount = 0;
    int order = 0;                   // degree + 1
    std::vector<double> knots;       // vertexCount + order, non-decreasing
    std::array<double, 2> range{};   // as authored; (0, 0): not authored
    // The range drawn: `range` when authored, else the whole valid range
    // [knots[order - 1], knots[vertexCount]].
    std::array<double, 2> drawnRange() const;
    // Knot spans (the intervals [knots[i], knots[i + 1]] for i in [order - 1, vertexCount - 1],
    // zero-length ones included): what uniform and varying primvars count their elements by.
    int spanCount() const { return vertexCount - order + 1; }
};

struct NurbsPatchInput {
    std::vector<float> points;  // xyz, u varying fastest
    NurbsDirection u, v;
    std::vector<float> pointWeights;  // empty: polynomial; else one positive weight per point
    bool leftHanded = false;
    // Primvars by the schema's element counts for patches: constant 1, uniform one per span
    // (spanCount u x v), varying and faceVarying one per span corner ((spanCount + 1) each way),
    // vertex one per control point (interpolated with the surface's own basis).
    std::optional<MeshPrimvar> displayColor;    // 3 components
    std::optional<MeshPrimvar> displayOpacity;  // 1 component
    std::optional<MeshPrimvar> st;              // 2 components; not authored: (u, v) normalised over the drawn range
};

// The highest order read: a patch of higher order is refused (bad data rather than a slow one).
constexpr int kMaxNurbsOrder = 16;

// Why the patch cannot be drawn ("uKnots has 9 values but uVertexCount + uOrder is 8",
// "vKnots decrease at [4]", "pointWeights[2] is 0; weights must be positive"...), or "".
// Primvars of a count no interpolation allows are dropped by the tessellation with a warning.
std::string nurbsPatchProblem(const NurbsPatchInput& patch);

// How far the surface bends within a span, per direction: the largest second derivative along u
// (and v) with the parameter normalised to each drawn span, in object units, at several points
// per span. A span cut into n steps stays within
// bend / (8 n^2) of its chords (the sagitta of a curve of second derivative M over 1/n is M / (8 n^2)).
std::array<double, 2> nurbsBendMagnitude(const NurbsPatchInput& patch);

// Knot spans of non-zero length within the drawn range, per direction.
std::array<int, 2> nurbsDrawnSpans(const NurbsPatchInput& patch);

// Triangles the tessellation at `steps` (per drawn span, u and v) makes, without making them.
uint64_t nurbsTriangleCount(const NurbsPatchInput& patch, std::array<int, 2> steps);

// The surface as a grid of quads, `steps` per drawn span each way: points on the surface, its
// exact normals (dS/du x dS/dv for rightHanded, turned for leftHanded; where that vanishes, at a
// pole, the normal a little inside the span), st and the display primvars per vertex (per face
// for uniform). Faces wind counter-clockwise in (u, v), so the mesh path's orientation rule makes
// the rightHanded front face the one dS/du x dS/dv points out of. Warnings for dropped primvars.
// The patch must be valid (nurbsPatchProblem).
struct NurbsTessellation {
    MeshInput mesh;
    std::vector<std::string> warnings;
};
NurbsTessellation tessellateNurbsPatch(const NurbsPatchInput& patch, std::array<int, 2> steps);

}  // namespace obscura::delegate
