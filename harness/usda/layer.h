// One parsed .usda file (an Sdf layer): its metadata and a tree of prim specs, as written,
// before composition. Paths inside are absolute in the layer's own namespace.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "harness/usda/list_op.h"
#include "harness/usda/stage.h"
#include "harness/usda/value_types.h"

namespace obscura::usda {

// Sdf's layer offset: time t of the layer (or prim) an arc or sublayer brings in is
// offset + scale * t where the arc is authored.
struct LayerOffset {
    double offset = 0.0;
    double scale = 1.0;
    double apply(double t) const { return offset + scale * t; }
    // This offset applied after `inner`: t -> apply(inner.apply(t)).
    LayerOffset after(const LayerOffset& inner) const { return {offset + scale * inner.offset, scale * inner.scale}; }
    bool isIdentity() const { return offset == 0.0 && scale == 1.0; }
};

// A reference or payload (asset path and/or prim path), or an inherits/specializes/sublayer
// entry (only one of the two paths set).
struct Reference {
    std::string assetPath;  // as written; empty for internal arcs
    std::string primPath;   // empty: the referenced layer's defaultPrim
    SourceLocation where;
    LayerOffset layerOffset;  // references, payloads and sublayers
    bool operator==(const Reference& other) const {
        return assetPath == other.assetPath && primPath == other.primPath;
    }
};

struct AttributeSpec {
    std::string typeName;  // as written: "uniform point3f[]"
    const ValueType* type = nullptr;
    bool isArray = false;
    bool isUniform = false;
    bool isCustom = false;
    std::optional<Value> defaultValue;  // a blocked Value for "= None"
    // "= AnimationBlock" (OpenUSD 25.05): weaker opinions' time samples are blocked, their defaults
    // still show (Composer's value resolution).
    bool animationBlock = false;
    std::optional<std::map<double, Value>> timeSamples;
    std::shared_ptr<const Spline> spline;  // ".spline = { ... }" on a scalar floating-point attribute
    ListOp<std::string> connections;
    std::map<std::string, Value> metadata;
    SourceLocation where;
};

struct RelationshipSpec {
    bool isCustom = false;
    ListOp<std::string> targets;
    std::map<std::string, Value> metadata;
    SourceLocation where;
};

struct PrimSpec;

struct VariantSetSpec {
    // Each variant's contents: a prim-like spec with metadata, arcs, properties and children.
    std::map<std::string, std::unique_ptr<PrimSpec>> variants;
};

struct PrimSpec {
    Specifier specifier = Specifier::Over;  // variant contents count as "over"
    std::string typeName;
    std::string name;
    SourceLocation where;
    std::map<std::string, Value> metadata;  // dictionaries flattened: "customData:key"
    ListOp<Reference> references, payloads, inherits, specializes;
    ListOp<std::string> apiSchemas;
    std::map<std::string, std::string> variantSelections;
    std::map<std::string, VariantSetSpec> variantSets;
    std::map<std::string, AttributeSpec> attributes;
    std::map<std::string, RelationshipSpec> relationships;
    std::vector<std::unique_ptr<PrimSpec>> children;  // in file order
    std::unordered_map<std::string, PrimSpec*> childByName;

    const PrimSpec* child(const std::string& childName) const {
        const auto it = childByName.find(childName);
        return it == childByName.end() ? nullptr : it->second;
    }
};

// A warning with the kind it is deduplicated by.
struct Diagnostic {
    std::string kind;
    Warning warning;
};

struct Layer {
    std::string identifier;  // the file path, as used in messages and to anchor asset paths
    std::map<std::string, Value> metadata;
    std::vector<Reference> subLayers;  // assetPath set
    PrimSpec pseudoRoot;               // its children are the root prims
    std::vector<Diagnostic> diagnostics;

    // The spec at a site path such as "/A{lod=hi}/B", or nullptr.
    const PrimSpec* find(std::string_view sitePath) const;
};

}  // namespace obscura::usda
