// UsdGeomBasisCurves and UsdGeomPoints turned into the triangles the mesh path draws: curves as
// tubes (or, with authored normals, ribbons facing them), points as spheres. Pure CPU code: no
// Vulkan, unit-tested on its own.
//
// The basis, wrap, segment counts, phantom points of pinned curves and primvar interpolation
// follow the UsdGeomBasisCurves schema documentation ("Segment Indexing", "Primvar
// Interpolation"); the cubic bases are the standard Bezier, uniform B-spline and Catmull-Rom ones
// (Foley, van Dam et al., "Computer Graphics", 11.2).
#pragma once

#include "delegate/mesh_builder.h"

#include <array>
#include <string>
#include <vector>

namespace obscura::delegate {

enum class CurveBasis { Linear, Bezier, Bspline, CatmullRom };
enum class CurveWrap { Nonperiodic, Periodic, Pinned };

struct CurvesInput {
    std::vector<float> points;  // xyz
    std::vector<int32_t> curveVertexCounts;
    CurveBasis basis = CurveBasis::Linear;  // `type` linear, else `basis`
    CurveWrap wrap = CurveWrap::Nonperiodic;
    std::optional<MeshPrimvar> widths;        // 1 component; not authored: 1 scene unit (Hydra's fallback)
    std::optional<MeshPrimvar> normals;       // authored: ribbons facing them, else tubes
    std::optional<MeshPrimvar> displayColor;  // 3 components
    std::optional<MeshPrimvar> displayOpacity;  // non-constant (a constant one is the gprim's)
};

// Segments of one curve of `vertexCount` control points (USD's segment indexing), or -1 where the
// count is too small for the basis and wrap (or not 4 + 3k for a nonperiodic Bezier, 3k periodic).
int curveSegmentCount(CurveBasis basis, CurveWrap wrap, int vertexCount);

// Elements a primvar of `interpolation` needs on these curves: constant 1, uniform one per
// curve, varying (and faceVarying) one per segment end, vertex one per point.
size_t curvePrimvarElementCount(const CurvesInput& curves, ObscuraInterpolation interpolation);

// Why the curves cannot be drawn ("curveVertexCounts sum to 7 but there are 8 points",
// "widths[3] is -0.5; widths must not be negative", a widths count the interpolation does not
// allow...), or "". Normals, displayColor and displayOpacity of the wrong size are dropped with a
// warning instead.
std::string curvesProblem(const CurvesInput& curves);

// Weights of the control points (indices within the curve, phantom points folded into the real
// ones they are made of) at parameter t in [0, 1] of segment `segment`, with d/dt of each.
struct CurveWeights {
    int count = 0;
    std::array<int, 4> index{};
    std::array<double, 4> weight{}, derivative{};
};
CurveWeights curveWeights(CurveBasis basis, CurveWrap wrap, int vertexCount, int segment, double t);

// How finely curves are cut: `sides` around a tube (ribbons have none), `steps` per segment of a
// cubic curve (linear segments are straight: always 1).
struct CurveDetail {
    int sides = 8;
    int steps = 1;
};

// Triangles the tessellation at `detail` makes, without making them.
uint64_t curveTriangleCount(const CurvesInput& curves, const CurveDetail& detail);

// The largest second difference of any cubic segment's control points in Bezier form, in object
// units: a segment cut into n steps stays within 6 M / (8 n^2) of its chords (the second
// derivative of a cubic Bezier is at most 6 times its largest control second difference).
double curveBendMagnitude(const CurvesInput& curves);

// The largest half width (tube radius) of the curves.
double curveMaxRadius(const CurvesInput& curves);

// Tubes (closed with flat caps unless periodic) or two-sided ribbons of the validated curves,
// indexed; vertices carry normals, displayColor (else 0.18 grey) and displayOpacity (else 1),
// tangents along the curve and uv (u along the curve, v around it). Warnings for dropped primvars.
MeshGeometry tessellateCurves(const CurvesInput& curves, const CurveDetail& detail);

// UsdGeomPoints: spheres of diameter `widths` (constant, or one per point; not authored: 1)
// centred at the points.
struct PointsInput {
    std::vector<float> points;
    std::optional<MeshPrimvar> widths;
    std::optional<MeshPrimvar> displayColor;
    std::optional<MeshPrimvar> displayOpacity;  // one per point (a constant one is the gprim's)
};
std::string pointsProblem(const PointsInput& points);
// Half the width of point `index` of validated points.
double pointRadius(const PointsInput& points, size_t index);
// Triangles of pointImpostorBoxes: 12 per point.
uint64_t pointTriangleCount(const PointsInput& points);
// Each validated point as the cube that bounds its sphere (8 corners, 12 outward triangles),
// drawn as a sphere impostor (shaders/common/sphere_impostor.glsl): each corner carries, in the
// tangent's place, its offset from the point (xyz) and the sphere's radius (w); its normal points
// away from the point; its colour is the point's displayColor (else 0.18 grey) and displayOpacity
// (else 1).
MeshGeometry pointImpostorBoxes(const PointsInput& points);

}  // namespace obscura::delegate
