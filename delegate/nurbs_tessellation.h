// UsdGeomNurbsPatch turned into the polygons the mesh path draws: the rational B-spline surface
// itself, evaluated on a grid of steps per knot span, not its control hull (which is what Storm
// draws). Pure CPU code: no Vulkan, unit-tested on its own.
//
// The encoding is the schema's (after RiNuPatch): uVertexCount x vVertexCount control points with
// u varying fastest, knot vectors of vertexCount + order values, optional weights (rational) and
// parameter ranges. Basis functions and their derivatives by the Cox-de Boor recursion (Piegl and
// Tiller, "The NURBS Book", 2nd ed., eq. 2.5 and 2.7); rational derivatives by eq. 4.8.
// Trim curves (nurbs_trim.h) cut the grid's cells where they cross them; Storm draws the untrimmed
// surface.
#pragma once

#include "delegate/mesh_builder.h"
#include "delegate/nurbs_basis.h"
#include "delegate/nurbs_trim.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace obscura::delegate {

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
    NurbsTrimCurves trimCurves;                 // none: untrimmed
};

// Why the patch cannot be drawn ("uKnots has 9 values but uVertexCount + uOrder is 8",
// "vKnots decrease at [4]", "pointWeights[2] is 0; weights must be positive"...), or "".
// Primvars of a count no interpolation allows are dropped by the tessellation with a warning.
std::string nurbsPatchProblem(const NurbsPatchInput& patch);

// How far the surface bends within a span, per direction: the largest second derivative along u
// (and v) with the parameter normalised to each drawn span, in object units, at several points
// per span. A span cut into n steps stays within
// bend / (8 n^2) of its chords (the sagitta of a curve of second derivative M over 1/n is M / (8 n^2)).
std::array<double, 2> nurbsBendMagnitude(const NurbsPatchInput& patch);

// The steps per span (u, v) that cut every trim loop into at least kTrimCellsPerLoop cells each
// way (at most kMaxTrimStepsPerSpan), so that no loop falls between the grid's lines; (1, 1)
// untrimmed. Within a cell the trim boundary is straight, so a round hole is a polygon of at least
// about 3 kTrimCellsPerLoop sides.
constexpr double kTrimCellsPerLoop = 16.0;
constexpr int kMaxTrimStepsPerSpan = 256;
std::array<int, 2> nurbsTrimSteps(const NurbsPatchInput& patch);

// The bend (as nurbsBendMagnitude's, per direction) that keeps the trim boundary's chords within
// the same bound: a boundary of radius R cut by a step of h departs from it by h^2 / (8 R), the
// sagitta of a span L long cut in n steps bending by L^2 / R. R is the smallest loop's half extent,
// both measured through the control net's length per unit of parameter; (0, 0) untrimmed.
std::array<double, 2> nurbsTrimBend(const NurbsPatchInput& patch);

// Knot spans of non-zero length within the drawn range, per direction.
std::array<int, 2> nurbsDrawnSpans(const NurbsPatchInput& patch);

// Triangles the tessellation at `steps` (per drawn span, u and v) makes, without making them.
uint64_t nurbsTriangleCount(const NurbsPatchInput& patch, std::array<int, 2> steps);

// The surface as a grid of quads, `steps` per drawn span each way, cut by the trim curves (a grid
// point cut away stays, unused): points on the surface, its exact normals (dS/du x dS/dv for
// rightHanded, turned for leftHanded; where that vanishes, at a pole, the normal a little inside
// the span), st and the display primvars per vertex (per face for uniform). Faces wind counter-clockwise in (u, v), so the mesh path's orientation rule makes
// the rightHanded front face the one dS/du x dS/dv points out of. Warnings for dropped primvars.
// The patch must be valid (nurbsPatchProblem).
struct NurbsTessellation {
    MeshInput mesh;
    std::vector<std::string> warnings;
};
NurbsTessellation tessellateNurbsPatch(const NurbsPatchInput& patch, std::array<int, 2> steps);

}  // namespace obscura::delegate
