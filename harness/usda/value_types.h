// The value types an attribute can be declared with, and how each is laid out in a Value.
#pragma once

#include <string_view>

namespace obscura::usda {

enum class ScalarKind { Bool, Integer, Real, String, Token, Asset };

struct ValueType {
    std::string_view name;  // "float3", "matrix4d", "token"
    ScalarKind scalar;
    int tupleSize;          // components per element
    int rows;               // rows of a matrix (tupleSize == rows * rows); 0 otherwise
    bool quaternion;        // written (real, i, j, k); interpolated by slerp
};

// The type named as in a .usda file (without "[]"), or nullptr when USD has no such type.
const ValueType* findValueType(std::string_view name);

}  // namespace obscura::usda
