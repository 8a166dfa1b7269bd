// One parametric direction of a non-uniform rational B-spline, and its basis functions: what the
// NURBS patch's surface (nurbs_tessellation.h) and its trim curves (nurbs_trim.h) are evaluated
// with. Basis functions and their derivatives by the Cox-de Boor recursion (Piegl and Tiller,
// "The NURBS Book", 2nd ed., eq. 2.5 and 2.7).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace obscura::delegate {

// The highest order read: a patch or trim curve of higher order is refused (bad data rather than
// a slow one).
constexpr int kMaxNurbsOrder = 16;

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

// What a direction's values are called where a problem names them: "uOrder", "uVertexCount",
// "uKnots", "uRange" for a patch's u.
struct NurbsDirectionNames {
    std::string order, vertexCount, knots, range;
};

// Why an order and vertex count make no B-spline ("uOrder is 17; it must be 2 to 16", "uVertexCount
// is 2; it must be at least uOrder (3)"), or "".
std::string nurbsOrderProblem(int order, int vertexCount, const NurbsDirectionNames& names);

// Why the direction is no B-spline ("uKnots has 9 values but uVertexCount + uOrder is 8", "uKnots
// decrease at [4]", ...), or "".
std::string nurbsDirectionProblem(const NurbsDirection& d, const NurbsDirectionNames& names);

using NurbsFunctions = std::array<double, kMaxNurbsOrder>;

// The order non-zero basis functions N_{first + k} (k = 0..degree) of one direction at t within
// knot span `span` (knots[span] <= t <= knots[span + 1]), and their first and second derivatives.
struct SpanBasis {
    int first = 0;
    NurbsFunctions value{}, derivative{}, second{};
};
SpanBasis basisAt(const NurbsDirection& d, int span, double t);

}  // namespace obscura::delegate
