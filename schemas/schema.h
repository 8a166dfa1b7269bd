// Prim schemas: what the delegate accepts from a host for each prim type, attribute by
// attribute. The data lives in schemas/*.json; the build turns it into static tables (the
// generated obscura_schema_tables.cpp) and into docs/schemas.md, so code and documentation
// cannot disagree.
#pragma once

#include <obscura/obscura.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace obscura::schema {

// Value types of schema attributes; the array types end in "Array" ("float3[]" in the JSON).
enum class AttrType {
    Bool,
    Int,
    Float,
    Double,
    Float2,
    Float3,
    Float4,
    Int2,
    Matrix4d,
    Token,
    Path,
    IntArray,
    FloatArray,
    Float2Array,
    Float3Array,
    Float4Array,
    PathArray
};

// The JSON spelling of a type: "bool", "float3[]", "matrix4d"...
const char* typeName(AttrType type);

struct AttributeSchema {
    const char* name;              // as in USD: "points", "inputs:roughness"
    AttrType type;
    const char* usdType;           // as USD declares it: "point3f[]", "uniform token", "rel"
    uint32_t defaultCount;         // 0 = no default; else numbers used in defaultNumbers, or 1 for a token/path
    double defaultNumbers[16];     // bool as 0/1, vectors component-wise, matrix4d row-major
    const char* defaultToken;      // token/path defaults, else nullptr
    const char* units;             // "" when the value has no unit
    bool timeSampled;              // USD allows time samples (false: uniform)
    uint32_t dirtyBit;             // OBSCURA_DIRTY_* value that makes the delegate re-read it
    const char* interpolation;     // default primvar interpolation ("vertex"...) or nullptr
    const char* const* tokens;     // allowed values of a token attribute, nullptr = any
    uint32_t tokenCount;
    const char* doc;
};

struct PrimSchema {
    const char* name;              // the prim type token of insertPrim: "mesh", "camera"...
    const char* usdType;           // USD schema it follows: "Mesh", "Camera"...
    const char* category;          // "rprim", "sprim" or "bprim"
    const AttributeSchema* attributes;
    uint32_t attributeCount;
    const char* doc;
};

// Every prim type, in the order of the schema files given to the generator.
std::span<const PrimSchema> primSchemas();

// nullptr when no prim type / attribute has that name.
const PrimSchema* findPrimSchema(std::string_view name);
const AttributeSchema* findAttribute(const PrimSchema& prim, std::string_view name);
// The same for names the caller knows the schemas declare: a miss is a programming error
// (std::logic_error naming both).
const AttributeSchema& attributeOf(const PrimSchema& prim, std::string_view name);
const AttributeSchema& attributeOf(std::string_view prim, std::string_view name);

// Component `component` of a numeric attribute's default, and a token attribute's default: what a
// host that authors nothing gets (the harness frames a scene with the default lens).
double defaultNumber(std::string_view prim, std::string_view attribute, size_t component = 0);
std::string_view defaultToken(std::string_view prim, std::string_view attribute);

// Checks a value the host returned for `attribute`: its type and shape fit the schema type,
// numbers are finite, tokens are among the allowed ones and paths are absolute. Returns "" when
// the value is acceptable, else a reason naming the attribute ("inputs:roughness: expected
// float, got token", "points: element 12 is NaN").
// Accepted value types: bool <- BOOL (0 or 1) or INT (nonzero = true); float, double and float[]
// <- FLOAT or DOUBLE (the caller converts); int2 <- INT2; int[] <- INT array; every other type
// only its own ObscuraValueType. Array types require isArray = 1 (any count, data non-null when
// count > 0); scalar types require isArray = 0 and count = 1.
std::string checkValue(const AttributeSchema& attribute, const ObscuraValue& value);

}  // namespace obscura::schema
