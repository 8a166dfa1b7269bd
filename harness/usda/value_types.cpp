#include "harness/usda/value_types.h"

#include <array>

namespace obscura::usda {

namespace {

using K = ScalarKind;

// Role types (point3f, color3f, ...) share the layout of their underlying vector type.
constexpr std::array kTypes = {
    ValueType{"bool", K::Bool, 1, 0, false},       ValueType{"uchar", K::Integer, 1, 0, false},
    ValueType{"int", K::Integer, 1, 0, false},     ValueType{"uint", K::Integer, 1, 0, false},
    ValueType{"int64", K::Integer, 1, 0, false},   ValueType{"uint64", K::Integer, 1, 0, false},
    ValueType{"half", K::Real, 1, 0, false},       ValueType{"float", K::Real, 1, 0, false},
    ValueType{"double", K::Real, 1, 0, false},     ValueType{"timecode", K::Real, 1, 0, false},
    ValueType{"string", K::String, 1, 0, false},   ValueType{"token", K::Token, 1, 0, false},
    ValueType{"asset", K::Asset, 1, 0, false},
    // A path expression (UsdCollectionAPI's membershipExpression) is written as a string.
    ValueType{"pathExpression", K::String, 1, 0, false},
    // An opaque attribute (and a group, which is one) holds no value: it is declared and connected.
    ValueType{"opaque", K::Token, 1, 0, false},     ValueType{"group", K::Token, 1, 0, false},
    ValueType{"int2", K::Integer, 2, 0, false},    ValueType{"int3", K::Integer, 3, 0, false},
    ValueType{"int4", K::Integer, 4, 0, false},
    ValueType{"half2", K::Real, 2, 0, false},      ValueType{"half3", K::Real, 3, 0, false},
    ValueType{"half4", K::Real, 4, 0, false},
    ValueType{"float2", K::Real, 2, 0, false},     ValueType{"float3", K::Real, 3, 0, false},
    ValueType{"float4", K::Real, 4, 0, false},
    ValueType{"double2", K::Real, 2, 0, false},    ValueType{"double3", K::Real, 3, 0, false},
    ValueType{"double4", K::Real, 4, 0, false},
    ValueType{"point3h", K::Real, 3, 0, false},    ValueType{"point3f", K::Real, 3, 0, false},
    ValueType{"point3d", K::Real, 3, 0, false},
    ValueType{"normal3h", K::Real, 3, 0, false},   ValueType{"normal3f", K::Real, 3, 0, false},
    ValueType{"normal3d", K::Real, 3, 0, false},
    ValueType{"vector3h", K::Real, 3, 0, false},   ValueType{"vector3f", K::Real, 3, 0, false},
    ValueType{"vector3d", K::Real, 3, 0, false},
    ValueType{"color3h", K::Real, 3, 0, false},    ValueType{"color3f", K::Real, 3, 0, false},
    ValueType{"color3d", K::Real, 3, 0, false},
    ValueType{"color4h", K::Real, 4, 0, false},    ValueType{"color4f", K::Real, 4, 0, false},
    ValueType{"color4d", K::Real, 4, 0, false},
    ValueType{"texCoord2h", K::Real, 2, 0, false}, ValueType{"texCoord2f", K::Real, 2, 0, false},
    ValueType{"texCoord2d", K::Real, 2, 0, false},
    ValueType{"texCoord3h", K::Real, 3, 0, false}, ValueType{"texCoord3f", K::Real, 3, 0, false},
    ValueType{"texCoord3d", K::Real, 3, 0, false},
    ValueType{"quath", K::Real, 4, 0, true},       ValueType{"quatf", K::Real, 4, 0, true},
    ValueType{"quatd", K::Real, 4, 0, true},
    ValueType{"matrix2d", K::Real, 4, 2, false},   ValueType{"matrix3d", K::Real, 9, 3, false},
    ValueType{"matrix4d", K::Real, 16, 4, false},  ValueType{"frame4d", K::Real, 16, 4, false},
};

}  // namespace

const ValueType* findValueType(std::string_view name) {
    for (const ValueType& type : kTypes)
        if (type.name == name) return &type;
    return nullptr;
}

}  // namespace obscura::usda
