// SdfVariableExpression (OpenUSD "Variable Expressions"): an asset path of an arc, a sublayer or an
// asset-valued attribute, or a variant selection, written between backticks is an expression over the layer stack's
// `expressionVariables` (layer metadata): a string with `${NAME}` substitutions (`"./a_${SHOT}.usd"`),
// a variable alone (`${SHOT}`), the literals None, true/false, integers and lists, and the functions
// if(cond, a[, b]), and(...), or(...), not(a), eq/neq/lt/leq/gt/geq(a, b), contains(list or
// string, x), at(list or string, i), len(x) and defined(NAME, ...).
#pragma once

#include "harness/usda/stage.h"

#include <map>
#include <string>
#include <variant>

namespace obscura::usda {

// A layer's expressionVariables by name (metadata "expressionVariables:NAME").
using ExpressionVariables = std::map<std::string, Value>;
ExpressionVariables expressionVariablesOf(const std::map<std::string, Value>& layerMetadata);

// Whether `text` is an expression (enclosed in backticks).
bool isVariableExpression(const std::string& text);

// The string an expression evaluates to ("" for None), or what is wrong with it.
struct ExpressionProblem {
    std::string message;
};
std::variant<std::string, ExpressionProblem> evaluateVariableExpression(const std::string& text,
                                                                        const ExpressionVariables& variables);

}  // namespace obscura::usda
