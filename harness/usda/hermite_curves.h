// UsdGeomHermiteCurves as cubic Bezier curves (bezier_curves.h), exactly: the segment between
// points k and k + 1 has the control points P_k, P_k + T_k / 3, P_{k+1} - T_{k+1} / 3, P_{k+1}
// (a cubic Hermite segment's Bezier form; T the authored tangents). Vertex primvars have no
// tangents: they run linearly along each segment, as varying ones do.
#pragma once

#include "harness/usda/bezier_curves.h"

#include <variant>
#include <vector>

namespace obscura::usda {

// The Bezier form of Hermite curves of `curveVertexCounts` (at least 2 each) over `pointCount`
// points and `tangentCount` tangents (one per point), or what makes them unusable.
std::variant<BezierCurves, AttributeProblem> hermiteToBezier(const std::vector<int>& curveVertexCounts, size_t pointCount,
                                                             size_t tangentCount);

// The same for a HermiteCurves prim's attributes at `time`.
std::variant<BezierCurves, AttributeProblem> hermiteCurvesAsBezier(const Prim& prim, double time);

}  // namespace obscura::usda
