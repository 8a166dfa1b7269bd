// UsdGeomNurbsCurves as cubic Bezier curves (bezier_curves.h). Each knot span of non-zero length
// within a curve's range becomes Bezier segments in Hermite form: the ends P(t0), P(t1) and the
// inner control points P(t0) + h/3 P'(t0), P(t1) - h/3 P'(t1) (h = t1 - t0), P and P' evaluated from
// the rational basis functions (Cox-de Boor recursion). That is exact for polynomial spans of order
// 2 to 4 (a cubic Hermite segment reproduces every polynomial of degree 3 or less), so those take
// one segment per span; rational spans and orders above 4 are cut into pieces until the Hermite
// form stays within kNurbsTolerance of the curve (nurbs_curves.cpp says how that is measured).
// Periodic curves are authored through their knots and repeated points (the schema's `form` is
// informative): they are evaluated like any other.
#pragma once

#include "harness/usda/bezier_curves.h"

#include <variant>
#include <vector>

namespace obscura::usda {

// The largest distance of the Bezier form from the curve, as a share of the radius of the
// smallest sphere around the control points of the span: 1e-4 keeps a curve that fills a 4K frame
// (a radius of some 2000 pixels) within 0.2 pixels of its exact silhouette.
constexpr double kNurbsTolerance = 1e-4;
// Pieces one span is cut into at most, whatever its weights ask for.
constexpr int kNurbsMaxPiecesPerSpan = 64;

struct NurbsCurvesData {
    std::vector<int> curveVertexCounts;
    std::vector<int> order;           // per curve: degree + 1
    std::vector<double> knots;        // every curve's nVerts + order knots, one curve after another
    std::vector<double> ranges;       // (min, max) per curve; empty: each curve's knots[order - 1], knots[nVerts]
    std::vector<double> pointWeights;  // per point; empty: polynomial curves
    size_t pointCount = 0;
};

// The Bezier form of `curves`, or the problem that makes them unusable (counts that do not add up,
// decreasing knots, an order outside [2, nVerts], weights that are not positive, ranges outside
// the knots).
std::variant<BezierCurves, AttributeProblem> nurbsToBezier(const NurbsCurvesData& curves);

// The same for a NurbsCurves prim's attributes at `time`.
std::variant<BezierCurves, AttributeProblem> nurbsCurvesAsBezier(const Prim& prim, double time);

}  // namespace obscura::usda
