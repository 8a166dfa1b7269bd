#include "harness/usda/bezier_curves.h"

#include <algorithm>

namespace obscura::usda {

void LinearCombination::addRow(size_t firstColumn, const std::vector<double>& rowWeights) {
    for (size_t k = 0; k < rowWeights.size(); ++k) {
        if (rowWeights[k] == 0.0) continue;
        columns.push_back(firstColumn + k);
        weights.push_back(rowWeights[k]);
    }
    rowStarts.push_back(columns.size());
}

void LinearCombination::addRow(const std::vector<std::pair<size_t, double>>& terms) {
    for (const auto& [column, weight] : terms) {
        columns.push_back(column);
        weights.push_back(weight);
    }
    rowStarts.push_back(columns.size());
}

std::vector<double> LinearCombination::apply(const std::vector<double>& input, size_t components) const {
    std::vector<double> out(rows() * components, 0.0);
    for (size_t row = 0; row < rows(); ++row)
        for (size_t k = rowStarts[row]; k < rowStarts[row + 1]; ++k)
            for (size_t c = 0; c < components; ++c) out[row * components + c] += weights[k] * input[columns[k] * components + c];
    return out;
}

std::variant<Value, std::string> convertCurvesPrimvar(const BezierCurves& curves, const Value& value,
                                                      const std::string& interpolation, size_t elementSize) {
    if (interpolation == "constant") return value;
    const size_t elements = value.size() / std::max<size_t>(1, elementSize);
    const size_t components = size_t(std::max(1, value.tupleSize)) * std::max<size_t>(1, elementSize);
    const bool uniform = interpolation == "uniform";
    const bool vertex = interpolation == "vertex";
    const size_t expected = uniform ? curves.authoredCurves : vertex ? curves.vertex.inputCount : curves.varying.inputCount;
    if (elements != expected || value.size() % std::max<size_t>(1, elementSize) != 0)
        return std::to_string(value.size()) + " values but " + interpolation + " interpolation needs " +
               std::to_string(expected * std::max<size_t>(1, elementSize));
    if (value.numbers.empty() && !value.strings.empty() && !uniform)
        return interpolation + " " + value.typeName + " values cannot be interpolated along the converted curves";
    Value converted = value;
    if (uniform) {
        // A curve cut apart where it is discontinuous keeps its value on every piece.
        std::vector<double> numbers;
        std::vector<std::string> strings;
        for (size_t source : curves.sourceCurves) {
            for (size_t c = 0; c < components && !value.numbers.empty(); ++c)
                numbers.push_back(value.numbers[source * components + c]);
            for (size_t e = 0; e < elementSize && value.numbers.empty(); ++e)
                strings.push_back(value.strings[source * elementSize + e]);
        }
        converted.numbers = std::move(numbers);
        converted.strings = std::move(strings);
        return converted;
    }
    converted.numbers = (vertex ? curves.vertex : curves.varying).apply(value.numbers, components);
    return converted;
}

SourceLocation whereAuthored(const Prim& prim, const std::string& attribute) {
    const Attribute* a = prim.attribute(attribute);
    return a ? a->where : prim.where;
}

}  // namespace obscura::usda
