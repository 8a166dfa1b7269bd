// UsdGeomNurbsPatch's trim curves (after RiTrimCurve): closed loops of rational B-spline curves in
// the patch's (u, v) parameter space that cut its surface. Pure CPU code, unit-tested on its own.
//
// Which side of a loop is kept, which the schema leaves unsaid, follows the convention of the
// modellers that write trimmed surfaces (OpenGL's gluBeginTrim, Maya's trimWithBoundaries): the
// surface to the left of each curve, so an outer boundary runs counter-clockwise in (u, v) and a
// hole clockwise; loops that are all holes (the largest loop clockwise) keep the patch's own
// boundary as the outer one. That is: a point is kept where the loops' winding number about it,
// plus 1 when the largest loop is clockwise, is positive.
#pragma once

#include "delegate/nurbs_basis.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace obscura::delegate {

// The trimCurve:* attributes as authored.
struct NurbsTrimCurves {
    std::vector<int32_t> counts;                 // curves per loop
    std::vector<int32_t> orders, vertexCounts;   // per curve
    std::vector<double> knots;                   // each curve's vertexCount + order, one curve after another
    std::vector<std::array<double, 2>> ranges;   // per curve; (0, 0) or none: its knots' whole valid range
    std::vector<std::array<double, 3>> points;   // homogeneous (u w, v w, w), vertexCount per curve
    bool empty() const { return counts.empty(); }
};

// Why the trim curves cannot be applied ("trimCurve:orders has 2 values but trimCurve:counts adds
// up to 3 curves", "trimCurve:points[4] has weight 0; weights must be positive", ...), or "".
std::string nurbsTrimProblem(const NurbsTrimCurves& curves);

// Where a grid line of the patch's parameter space is kept: the line v = `at` (direction 0, u
// along it) or u = `at` (direction 1), at increasing positions `along`.
struct NurbsTrimLine {
    std::vector<char> kept;       // per position
    // Per interval between positions: where the boundary crosses it (the last change of side, or
    // the last crossing where the ends do not differ), NaN where it does not.
    std::vector<double> crossing;
};

class NurbsTrimRegion {
public:
    // The curves must be valid (nurbsTrimProblem).
    explicit NurbsTrimRegion(const NurbsTrimCurves& curves);
    bool empty() const { return loops_.empty(); }
    NurbsTrimLine line(int direction, double at, const std::vector<double>& along) const;
    // The smallest extent of a loop along u and along v: the detail a tessellation must resolve.
    std::array<double, 2> smallestLoop() const;

private:
    using Point = std::array<double, 2>;
    std::vector<std::vector<Point>> loops_;  // closed: the last point joins the first
    int outsideWinding_ = 0;
};

}  // namespace obscura::delegate
