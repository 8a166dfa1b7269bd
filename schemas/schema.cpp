// Lookups over the generated schema tables and validation of host values against them.
#include "schemas/schema.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace obscura::schema {
namespace {

// How a schema type is carried in an ObscuraValue.
struct Shape {
    ObscuraValueType valueType;    // the exact type
    ObscuraValueType alternative;  // also accepted (the caller converts), or OBSCURA_VALUE_NONE
    bool isArray;
};

Shape shapeOf(AttrType type) {
    switch (type) {
    case AttrType::Bool: return {OBSCURA_VALUE_BOOL, OBSCURA_VALUE_INT, false};
    case AttrType::Int: return {OBSCURA_VALUE_INT, OBSCURA_VALUE_NONE, false};
    case AttrType::Float: return {OBSCURA_VALUE_FLOAT, OBSCURA_VALUE_DOUBLE, false};
    case AttrType::Double: return {OBSCURA_VALUE_DOUBLE, OBSCURA_VALUE_FLOAT, false};
    case AttrType::Float2: return {OBSCURA_VALUE_FLOAT2, OBSCURA_VALUE_NONE, false};
    case AttrType::Float3: return {OBSCURA_VALUE_FLOAT3, OBSCURA_VALUE_NONE, false};
    case AttrType::Float4: return {OBSCURA_VALUE_FLOAT4, OBSCURA_VALUE_NONE, false};
    case AttrType::Int2: return {OBSCURA_VALUE_INT2, OBSCURA_VALUE_NONE, false};
    case AttrType::Matrix4d: return {OBSCURA_VALUE_MATRIX4D, OBSCURA_VALUE_NONE, false};
    case AttrType::Token: return {OBSCURA_VALUE_TOKEN, OBSCURA_VALUE_NONE, false};
    case AttrType::Path: return {OBSCURA_VALUE_PATH, OBSCURA_VALUE_NONE, false};
    case AttrType::IntArray: return {OBSCURA_VALUE_INT, OBSCURA_VALUE_NONE, true};
    case AttrType::FloatArray: return {OBSCURA_VALUE_FLOAT, OBSCURA_VALUE_DOUBLE, true};
    case AttrType::Float2Array: return {OBSCURA_VALUE_FLOAT2, OBSCURA_VALUE_NONE, true};
    case AttrType::Float3Array: return {OBSCURA_VALUE_FLOAT3, OBSCURA_VALUE_NONE, true};
    case AttrType::Float4Array: return {OBSCURA_VALUE_FLOAT4, OBSCURA_VALUE_NONE, true};
    case AttrType::PathArray: return {OBSCURA_VALUE_PATH, OBSCURA_VALUE_NONE, true};
    }
    return {OBSCURA_VALUE_NONE, OBSCURA_VALUE_NONE, false};
}

// Value types spelt like schema types, so that "expected float3[], got float3" reads naturally;
// nullptr for a number outside the enum (a host bug worth naming in the message).
const char* valueTypeName(ObscuraValueType type) {
    switch (type) {
    case OBSCURA_VALUE_NONE: return "none";
    case OBSCURA_VALUE_BOOL: return "bool";
    case OBSCURA_VALUE_INT: return "int";
    case OBSCURA_VALUE_FLOAT: return "float";
    case OBSCURA_VALUE_DOUBLE: return "double";
    case OBSCURA_VALUE_FLOAT2: return "float2";
    case OBSCURA_VALUE_FLOAT3: return "float3";
    case OBSCURA_VALUE_FLOAT4: return "float4";
    case OBSCURA_VALUE_INT2: return "int2";
    case OBSCURA_VALUE_MATRIX4D: return "matrix4d";
    case OBSCURA_VALUE_TOKEN: return "token";
    case OBSCURA_VALUE_PATH: return "path";
    }
    return nullptr;
}

// Numbers per element of a numeric value type; 0 for the others.
size_t componentsOf(ObscuraValueType type) {
    switch (type) {
    case OBSCURA_VALUE_FLOAT2: return 2;
    case OBSCURA_VALUE_FLOAT3: return 3;
    case OBSCURA_VALUE_FLOAT4: return 4;
    case OBSCURA_VALUE_MATRIX4D: return 16;
    case OBSCURA_VALUE_FLOAT:
    case OBSCURA_VALUE_DOUBLE: return 1;
    default: return 0;
    }
}

std::string describe(const ObscuraValue& value) {
    const char* name = valueTypeName(value.type);
    if (!name) return "unknown value type " + std::to_string(static_cast<int>(value.type));
    return std::string(name) + (value.isArray ? "[]" : "");
}

// What a message calls the offending number: "element 12" of an array ("points: element 12 is
// NaN"), or the "value" of a scalar.
std::string elementLabel(const ObscuraValue& value, size_t index) {
    return value.isArray ? "element " + std::to_string(index) : "value";
}

template <typename T>
std::string checkFinite(const ObscuraValue& value, size_t components) {
    const T* numbers = static_cast<const T*>(value.data);
    for (size_t i = 0; i < value.count * components; ++i) {
        if (std::isnan(numbers[i])) return elementLabel(value, i / components) + " is NaN";
        if (std::isinf(numbers[i])) return elementLabel(value, i / components) + " is Inf";
    }
    return {};
}

std::string checkBool(const ObscuraValue& value) {
    // INT is accepted with C's meaning (nonzero is true); BOOL promises 0 or 1.
    if (value.type != OBSCURA_VALUE_BOOL) return {};
    const int32_t flag = *static_cast<const int32_t*>(value.data);
    if (flag != 0 && flag != 1) return "bool value is " + std::to_string(flag) + ", not 0 or 1";
    return {};
}

std::string checkStrings(const AttributeSchema& attribute, const ObscuraValue& value) {
    const char* const* strings = static_cast<const char* const*>(value.data);
    for (size_t i = 0; i < value.count; ++i) {
        const char* text = strings[i];
        if (!text) return elementLabel(value, i) + " is a null string";
        if (value.type == OBSCURA_VALUE_PATH && text[0] != '/')
            return "path \"" + std::string(text) + "\" is not absolute";
        if (attribute.tokenCount == 0) continue;
        bool allowed = false;
        for (uint32_t t = 0; t < attribute.tokenCount; ++t) allowed = allowed || std::strcmp(text, attribute.tokens[t]) == 0;
        if (!allowed) {
            std::string message = "\"" + std::string(text) + "\" is not one of ";
            for (uint32_t t = 0; t < attribute.tokenCount; ++t) message += (t ? ", " : "") + std::string(attribute.tokens[t]);
            return message;
        }
    }
    return {};
}

// The reason a value does not fit, without the attribute name.
std::string problem(const AttributeSchema& attribute, const ObscuraValue& value) {
    const Shape shape = shapeOf(attribute.type);
    const bool typeFits = value.type == shape.valueType || (shape.alternative != OBSCURA_VALUE_NONE && value.type == shape.alternative);
    if (!typeFits || (value.isArray != 0) != shape.isArray)
        return "expected " + std::string(typeName(attribute.type)) + ", got " + describe(value);
    if (!shape.isArray && value.count != 1) return "expected one value, got " + std::to_string(value.count);
    if (value.count > 0 && !value.data) return "data is null";
    if (value.count == 0) return {};

    switch (value.type) {
    case OBSCURA_VALUE_BOOL:
    case OBSCURA_VALUE_INT: return attribute.type == AttrType::Bool ? checkBool(value) : std::string();
    case OBSCURA_VALUE_DOUBLE:
    case OBSCURA_VALUE_MATRIX4D: return checkFinite<double>(value, componentsOf(value.type));
    case OBSCURA_VALUE_FLOAT:
    case OBSCURA_VALUE_FLOAT2:
    case OBSCURA_VALUE_FLOAT3:
    case OBSCURA_VALUE_FLOAT4: return checkFinite<float>(value, componentsOf(value.type));
    case OBSCURA_VALUE_TOKEN:
    case OBSCURA_VALUE_PATH: return checkStrings(attribute, value);
    case OBSCURA_VALUE_INT2:
    case OBSCURA_VALUE_NONE: return {};
    }
    return {};
}

}  // namespace

const char* typeName(AttrType type) {
    switch (type) {
    case AttrType::Bool: return "bool";
    case AttrType::Int: return "int";
    case AttrType::Float: return "float";
    case AttrType::Double: return "double";
    case AttrType::Float2: return "float2";
    case AttrType::Float3: return "float3";
    case AttrType::Float4: return "float4";
    case AttrType::Int2: return "int2";
    case AttrType::Matrix4d: return "matrix4d";
    case AttrType::Token: return "token";
    case AttrType::Path: return "path";
    case AttrType::IntArray: return "int[]";
    case AttrType::FloatArray: return "float[]";
    case AttrType::Float2Array: return "float2[]";
    case AttrType::Float3Array: return "float3[]";
    case AttrType::Float4Array: return "float4[]";
    case AttrType::PathArray: return "path[]";
    }
    return "unknown";
}

const PrimSchema* findPrimSchema(std::string_view name) {
    for (const PrimSchema& prim : primSchemas())
        if (name == prim.name) return &prim;
    return nullptr;
}

const AttributeSchema* findAttribute(const PrimSchema& prim, std::string_view name) {
    for (const AttributeSchema& attribute : std::span(prim.attributes, prim.attributeCount))
        if (name == attribute.name) return &attribute;
    return nullptr;
}

const AttributeSchema& attributeOf(const PrimSchema& prim, std::string_view name) {
    if (const AttributeSchema* found = findAttribute(prim, name)) return *found;
    throw std::logic_error("schema '" + std::string(prim.name) + "' has no attribute " + std::string(name));
}

const AttributeSchema& attributeOf(std::string_view prim, std::string_view name) {
    const PrimSchema* schema = findPrimSchema(prim);
    if (!schema) throw std::logic_error("no prim schema '" + std::string(prim) + "'");
    return attributeOf(*schema, name);
}

double defaultNumber(std::string_view prim, std::string_view name, size_t component) {
    const AttributeSchema& a = attributeOf(prim, name);
    if (component >= a.defaultCount || a.defaultToken)
        throw std::logic_error(std::string(prim) + "." + std::string(name) + " has no numeric default " +
                               std::to_string(component));
    return a.defaultNumbers[component];
}

std::string_view defaultToken(std::string_view prim, std::string_view name) {
    const AttributeSchema& a = attributeOf(prim, name);
    if (!a.defaultToken) throw std::logic_error(std::string(prim) + "." + std::string(name) + " has no token default");
    return a.defaultToken;
}

std::string checkValue(const AttributeSchema& attribute, const ObscuraValue& value) {
    std::string reason = problem(attribute, value);
    return reason.empty() ? reason : std::string(attribute.name) + ": " + reason;
}

}  // namespace obscura::schema
