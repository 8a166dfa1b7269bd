#include "harness/usda/hermite_curves.h"

#include <string>

namespace obscura::usda {

std::variant<BezierCurves, AttributeProblem> hermiteToBezier(const std::vector<int>& curveVertexCounts, size_t pointCount,
                                                             size_t tangentCount) {
    size_t points = 0;
    for (size_t i = 0; i < curveVertexCounts.size(); ++i) {
        if (curveVertexCounts[i] < 2)
            return AttributeProblem{"curveVertexCounts", "curveVertexCounts[" + std::to_string(i) + "] = " +
                                                             std::to_string(curveVertexCounts[i]) +
                                                             " is fewer than the 2 points of a segment"};
        points += size_t(curveVertexCounts[i]);
    }
    if (points != pointCount)
        return AttributeProblem{"curveVertexCounts", "curveVertexCounts add up to " + std::to_string(points) +
                                                         " but there are " + std::to_string(pointCount) + " points"};
    if (tangentCount != pointCount)
        return AttributeProblem{"tangents", "tangents has " + std::to_string(tangentCount) + " values but there are " +
                                                std::to_string(pointCount) + " points (one tangent each)"};
    BezierCurves out;
    out.authoredCurves = curveVertexCounts.size();
    out.positions.inputCount = 2 * pointCount;  // the points, then the tangents
    out.vertex.inputCount = out.varying.inputCount = pointCount;
    size_t first = 0;
    for (size_t curve = 0; curve < curveVertexCounts.size(); ++curve) {
        const size_t n = size_t(curveVertexCounts[curve]);
        out.curveVertexCounts.push_back(int(3 * (n - 1) + 1));
        out.sourceCurves.push_back(curve);
        for (size_t k = first; k < first + n; ++k) {
            out.varying.addRow(k, {1.0});
            if (k > first) {
                // The segment from point k - 1: its inner control points, then point k.
                const size_t tangent = pointCount + k - 1;
                out.positions.addRow({{k - 1, 1.0}, {tangent, 1.0 / 3.0}});
                out.positions.addRow({{k, 1.0}, {tangent + 1, -1.0 / 3.0}});
                out.vertex.addRow(k - 1, {2.0 / 3.0, 1.0 / 3.0});
                out.vertex.addRow(k - 1, {1.0 / 3.0, 2.0 / 3.0});
            }
            out.positions.addRow(k, {1.0});
            out.vertex.addRow(k, {1.0});
        }
        first += n;
    }
    return out;
}

std::variant<BezierCurves, AttributeProblem> hermiteCurvesAsBezier(const Prim& prim, double time) {
    auto value = [&](const char* name) {
        const Attribute* attribute = prim.attribute(name);
        return attribute ? attribute->evaluate(time) : std::nullopt;
    };
    std::vector<int> counts;
    if (auto authored = value("curveVertexCounts"))
        for (double n : authored->numbers) counts.push_back(n >= -2147483648.0 && n <= 2147483647.0 ? int(n) : -1);
    auto points = value("points");
    auto tangents = value("tangents");
    return hermiteToBezier(counts, points ? points->size() : 0, tangents ? tangents->size() : 0);
}

}  // namespace obscura::usda
