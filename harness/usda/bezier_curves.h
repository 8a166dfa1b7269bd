// Curves the plugin does not draw as authored (UsdGeomNurbsCurves, UsdGeomHermiteCurves) in the
// form it does: cubic Bezier UsdGeomBasisCurves (type cubic, basis bezier, wrap nonperiodic), as
// UsdImaging's adapters serve a USD prim type as one Hydra draws. Every converted value is a
// linear combination of the authored ones, so a conversion is kept as sparse matrices that points,
// widths, normals and primvars of one interpolation share; the curves' topology (knots, order,
// tangents' count) decides them, not the points, so animated points keep one topology.
#pragma once

#include "harness/usda/stage.h"

#include <cstddef>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace obscura::usda {

// A linear map from `inputCount` authored elements to the rows' elements: row r is the sum of
// weights[k] * input[columns[k]] for k in [rowStarts[r], rowStarts[r + 1]).
struct LinearCombination {
    size_t inputCount = 0;
    std::vector<size_t> rowStarts{0};
    std::vector<size_t> columns;
    std::vector<double> weights;

    size_t rows() const { return rowStarts.size() - 1; }
    // Appends a row of `weights` over the consecutive columns from `firstColumn`.
    void addRow(size_t firstColumn, const std::vector<double>& rowWeights);
    // Appends a row of (column, weight) terms.
    void addRow(const std::vector<std::pair<size_t, double>>& terms);
    // `input` of `components` numbers per element (inputCount of them) mapped element-wise.
    std::vector<double> apply(const std::vector<double>& input, size_t components) const;
};

struct BezierCurves {
    std::vector<int> curveVertexCounts;  // per Bezier curve: 3 * segments + 1
    std::vector<size_t> sourceCurves;    // per Bezier curve: the authored curve it draws
    // The control points from the authored points (a Hermite curve's from its points, then its
    // tangents: columns past the points index the tangents).
    LinearCombination positions;
    LinearCombination vertex;   // vertex values (one per authored point) -> one per control point
    LinearCombination varying;  // varying values (one per authored segment end) -> one per segment end
    size_t authoredCurves = 0;  // uniform values: one per authored curve
};

// A problem with a prim's authored data: the attribute it is about and what is wrong.
struct AttributeProblem {
    std::string attribute;
    std::string message;
};

// `value`, authored with `interpolation` (UsdGeomPrimvar's: constant, uniform, varying, vertex,
// faceVarying, which curves read as varying) on the authored curves, as the Bezier curves' value
// of the same interpolation; the problem when its count does not fit the authored curves.
std::variant<Value, std::string> convertCurvesPrimvar(const BezierCurves& curves, const Value& value,
                                                      const std::string& interpolation, size_t elementSize);

// The attribute's source location on `prim` (the prim's when it is not authored), for reports.
SourceLocation whereAuthored(const Prim& prim, const std::string& attribute);

}  // namespace obscura::usda
