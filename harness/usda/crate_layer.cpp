#include "harness/usda/crate_layer.h"

#include <algorithm>
#include <set>

#include "harness/usda/crate_spline.h"
#include "harness/usda/crate_values.h"

namespace obscura::usda {

namespace {

using crate::Failure;
using crate::PathNode;
using crate::SpecType;
using crate::Type;
using crate::ValueRep;

constexpr uint32_t kFieldSetEnd = ~0u;

// Fields the layer model keeps in its structure rather than as metadata.
const std::set<std::string, std::less<>> kStructuralFields = {
    "specifier", "typeName", "primChildren", "properties", "variantSetNames", "variantChildren",
    "targetChildren", "connectionChildren", "subLayerOffsets",
};

class LayerBuilder {
public:
    LayerBuilder(const crate::File& file, const std::string& identifier)
        : file_(file), values_(file), layer_(std::make_unique<Layer>()), where_{identifier, 0, 0},
          containers_(file.paths().size(), nullptr), resolved_(file.paths().size(), false) {
        layer_->identifier = identifier;
    }

    std::unique_ptr<Layer> build() {
        for (const crate::Spec& spec : file_.specs()) addSpec(spec);
        for (auto& [prim, order] : childOrder_) reorder(*prim, order);
        return std::move(layer_);
    }

private:
    struct FieldValue {
        const std::string& name;
        ValueRep rep;
        uint64_t at;  // where the value is stored, for messages
    };

    std::vector<FieldValue> fieldsOf(const crate::Spec& spec) const {
        std::vector<FieldValue> out;
        const auto& sets = file_.fieldSets();
        for (size_t i = spec.fieldSet; i < sets.size() && sets[i] != kFieldSetEnd; ++i) {
            const crate::Field& field = file_.fields()[sets[i]];
            out.push_back(FieldValue{file_.token(field.token, 0), field.rep, field.rep.payload()});
        }
        return out;
    }

    // The prim spec (or variant contents) a prim-like path names, created on first use;
    // nullptr for a variant set's own path. Built top-down without recursion.
    PrimSpec* container(uint64_t index) {
        std::vector<uint64_t> chain;
        for (uint64_t i = index; !resolved_[i];) {
            chain.push_back(i);
            const PathNode& node = file_.paths()[i];
            if (node.kind == PathNode::Kind::Root) break;
            i = static_cast<uint64_t>(node.parent);
        }
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const PathNode& node = file_.paths()[*it];
            PrimSpec* parent = node.kind == PathNode::Kind::Root ? nullptr : containers_[node.parent];
            PrimSpec* made = nullptr;
            switch (node.kind) {
            case PathNode::Kind::Root: made = &layer_->pseudoRoot; break;
            case PathNode::Kind::Prim: made = parent ? child(*parent, node.name) : nullptr; break;
            case PathNode::Kind::Variant:
                if (parent) {
                    VariantSetSpec& set = parent->variantSets[node.name];
                    if (!node.variant.empty()) made = variant(set, node.variant);
                }
                break;
            case PathNode::Kind::Property: break;
            }
            if (!made && node.kind != PathNode::Kind::Variant)
                throw Failure{0, "spec <" + node.text + "> is not inside a prim"};
            containers_[*it] = made;
            resolved_[*it] = true;
        }
        return containers_[index];
    }

    PrimSpec* child(PrimSpec& parent, const std::string& name) {
        if (const auto it = parent.childByName.find(name); it != parent.childByName.end()) return it->second;
        auto spec = std::make_unique<PrimSpec>();
        spec->name = name;
        spec->where = where_;
        PrimSpec* out = spec.get();
        parent.childByName[name] = out;
        parent.children.push_back(std::move(spec));
        return out;
    }

    PrimSpec* variant(VariantSetSpec& set, const std::string& name) {
        auto& slot = set.variants[name];
        if (!slot) {
            slot = std::make_unique<PrimSpec>();
            slot->name = name;
            slot->where = where_;
        }
        return slot.get();
    }

    void reorder(PrimSpec& prim, const std::vector<std::string>& order) {
        auto rank = [&](const std::unique_ptr<PrimSpec>& spec) {
            const auto it = std::find(order.begin(), order.end(), spec->name);
            return static_cast<size_t>(it - order.begin());
        };
        std::stable_sort(prim.children.begin(), prim.children.end(),
                         [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
    }

    void warn(const std::string& kind, const std::string& message) {
        layer_->diagnostics.push_back(Diagnostic{kind, Warning{where_, message}});
    }

    // A generic field as metadata: dictionaries flattened, plain values kept, others skipped.
    void addMetadata(std::map<std::string, Value>& metadata, const FieldValue& field) {
        if (field.rep.type() == Type::Dictionary) return values_.dictionary(field.rep, field.name + ":", metadata);
        if (auto value = values_.value(field.rep)) metadata[field.name] = std::move(*value);
    }

    void addSpec(const crate::Spec& spec) {
        const PathNode& node = file_.path(spec.path, 0);
        switch (spec.type) {
        case SpecType::PseudoRoot: return addPseudoRoot(spec);
        case SpecType::Prim:
        case SpecType::Variant:
            if (PrimSpec* prim = container(spec.path)) addPrim(spec, node, *prim);
            return;
        case SpecType::VariantSet: return addVariantSet(spec, node);
        case SpecType::Attribute: return addAttribute(spec, node);
        case SpecType::Relationship: return addRelationship(spec, node);
        default: return;  // connection, target and mapper specs hold nothing the layer model keeps
        }
    }

    void addPseudoRoot(const crate::Spec& spec) {
        std::vector<LayerOffset> subLayerOffsets;
        for (const FieldValue& field : fieldsOf(spec)) {
            if (field.name == "subLayers") {
                for (std::string& asset : values_.names(field.rep))
                    layer_->subLayers.push_back(Reference{std::move(asset), "", where_});
            } else if (field.name == "subLayerOffsets") {
                subLayerOffsets = values_.layerOffsets(field.rep);
            } else if (field.name == "primChildren") {
                childOrder_[&layer_->pseudoRoot] = values_.names(field.rep);
            } else if (field.name == "layerRelocates") {
                if (auto value = values_.value(field.rep)) layer_->metadata["relocates"] = std::move(*value);
            } else if (!kStructuralFields.count(field.name)) {
                addMetadata(layer_->metadata, field);
            }
        }
        // Fields come in any order; a file may write fewer offsets than sublayers (identity).
        for (size_t i = 0; i < std::min(subLayerOffsets.size(), layer_->subLayers.size()); ++i)
            layer_->subLayers[i].layerOffset = subLayerOffsets[i];
    }

    void addPrim(const crate::Spec& spec, const PathNode& node, PrimSpec& prim) {
        const std::string at = "<" + node.text + ">";
        for (const FieldValue& field : fieldsOf(spec)) {
            const std::string& name = field.name;
            if (name == "specifier") {
                const uint32_t specifier = values_.enumValue(field.rep);
                if (specifier > 2) throw Failure{0, at + ": unknown specifier " + std::to_string(specifier)};
                prim.specifier = specifier == 0 ? Specifier::Def : specifier == 1 ? Specifier::Over : Specifier::Class;
            } else if (name == "typeName") {
                if (auto value = values_.value(field.rep); value && !value->strings.empty()) prim.typeName = value->strings[0];
            } else if (name == "primChildren") {
                childOrder_[&prim] = values_.names(field.rep);
            } else if (name == "references") {
                prim.references = values_.arcListOp(field.rep, where_);
            } else if (name == "payload") {
                prim.payloads = values_.arcListOp(field.rep, where_);
            } else if (name == "inherits" || name == "specializes") {
                auto arcs = values_.nameListOp(field.rep).transformed(
                    [&](const std::string& path) { return Reference{"", path, where_}; });
                (name == "inherits" ? prim.inherits : prim.specializes) = std::move(arcs);
            } else if (name == "apiSchemas") {
                prim.apiSchemas = values_.nameListOp(field.rep);
            } else if (name == "variantSelection") {
                prim.variantSelections = values_.variantSelections(field.rep);
            } else if (!kStructuralFields.count(name)) {
                addMetadata(prim.metadata, field);
            }
        }
    }

    void addVariantSet(const crate::Spec& spec, const PathNode& node) {
        PrimSpec* owner = node.parent >= 0 ? container(static_cast<uint64_t>(node.parent)) : nullptr;
        if (!owner) throw Failure{0, "variant set <" + node.text + "> is not on a prim"};
        VariantSetSpec& set = owner->variantSets[node.name];
        for (const FieldValue& field : fieldsOf(spec))
            if (field.name == "variantChildren")
                for (const std::string& name : values_.names(field.rep)) variant(set, name);
    }

    PrimSpec& propertyOwner(const PathNode& node) {
        PrimSpec* owner = node.kind == PathNode::Kind::Property && node.parent >= 0
                              ? container(static_cast<uint64_t>(node.parent))
                              : nullptr;
        if (!owner || file_.paths()[node.parent].kind == PathNode::Kind::Root)
            throw Failure{0, "property <" + node.text + "> is not on a prim"};
        return *owner;
    }

    void addAttribute(const crate::Spec& spec, const PathNode& node) {
        PrimSpec& owner = propertyOwner(node);
        if (owner.relationships.count(node.name)) throw Failure{0, "<" + node.text + "> is both a relationship and an attribute"};
        AttributeSpec attr;
        attr.where = where_;
        std::string declared;
        std::optional<ValueRep> spline;
        for (const FieldValue& field : fieldsOf(spec)) {
            const std::string& name = field.name;
            if (name == "typeName") {
                if (auto value = values_.value(field.rep); value && !value->strings.empty()) declared = value->strings[0];
            } else if (name == "variability") {
                attr.isUniform = values_.enumValue(field.rep) != 0;  // 0 varying; 1 uniform (2, legacy config, too)
            } else if (name == "custom") {
                auto value = values_.value(field.rep);
                attr.isCustom = value && !value->numbers.empty() && value->numbers[0] != 0.0;
            } else if (name == "default") {
                attr.animationBlock = field.rep.type() == Type::AnimationBlock;
                if (!attr.animationBlock) attr.defaultValue = values_.value(field.rep);
            } else if (name == "timeSamples") {
                attr.timeSamples = values_.timeSamples(field.rep);
            } else if (name == "spline") {
                spline = field.rep;
            } else if (name == "connectionPaths") {
                attr.connections = values_.nameListOp(field.rep);
            } else if (!kStructuralFields.count(name)) {
                addMetadata(attr.metadata, field);
            }
        }
        const bool isArray = declared.size() > 2 && declared.ends_with("[]");
        const std::string base = isArray ? declared.substr(0, declared.size() - 2) : declared;
        attr.type = findValueType(base);
        if (!attr.type) {
            warn("attributeType", "<" + node.text + ">: unknown attribute type '" + declared + "'; attribute skipped");
            return;
        }
        attr.isArray = isArray;
        attr.typeName = (attr.isUniform ? "uniform " : "") + declared;
        // Values take the declared type's name ("point3f", not the stored "float3"), as in text.
        auto shape = [&](std::optional<Value>& value) {
            if (!value) return;
            if (!value->blocked && value->tupleSize != attr.type->tupleSize && !value->empty())
                throw Failure{0, "<" + node.text + ">: value of " + std::to_string(value->tupleSize) +
                                     " components for type '" + declared + "'"};
            value->typeName = attr.type->name;
            value->tupleSize = attr.type->tupleSize;
            value->isArray = isArray;
        };
        shape(attr.defaultValue);
        if (attr.timeSamples)
            for (auto& [time, sample] : *attr.timeSamples) {
                std::optional<Value> shaped = std::move(sample);
                shape(shaped);
                sample = std::move(*shaped);
            }
        if (spline) addSpline(attr, *spline, node);
        owner.attributes[node.name] = std::move(attr);
    }

    // A malformed spline loses the attribute only its spline, as a spline on a type no spline
    // animates does in text.
    void addSpline(AttributeSpec& attr, ValueRep rep, const PathNode& node) {
        if (!splineAnimates(attr.type->name, attr.isArray)) {
            warn("spline:" + node.text, "<" + node.text + ">: a spline on a " + attr.typeName +
                               ", which no spline animates (double, float, half and timecode do); its default and "
                               "time samples are used");
            return;
        }
        const std::string valueType(attr.type->name);
        if (rep.isInlined() && rep.type() == Type::Spline) {  // a spline without knots
            auto empty = std::make_shared<Spline>();
            empty->valueType = valueType;
            attr.spline = std::move(empty);
            return;
        }
        try {
            if (rep.type() != Type::Spline)
                throw Failure{rep.payload(), "a value of type " + std::to_string(int(rep.type())) + ", not a spline"};
            std::shared_ptr<const Spline> spline = crate::decodeSpline(file_.bytes(), rep.payload(), valueType);
            if (std::string problem = spline->innerLoopProblem(); !problem.empty()) {
                warn("spline:" + node.text,
                     "<" + node.text + ">: a spline that is left out: " + problem + "; its default and time samples are used");
                return;
            }
            attr.spline = std::move(spline);
        } catch (const Failure& failure) {
            warn("spline:" + node.text, "<" + node.text + ">: byte " + std::to_string(failure.offset) + ": malformed spline (" +
                               failure.message + "); the attribute's spline is skipped");
        }
    }

    void addRelationship(const crate::Spec& spec, const PathNode& node) {
        PrimSpec& owner = propertyOwner(node);
        if (owner.attributes.count(node.name)) throw Failure{0, "<" + node.text + "> is both an attribute and a relationship"};
        RelationshipSpec& rel = owner.relationships[node.name];
        rel.where = where_;
        for (const FieldValue& field : fieldsOf(spec)) {
            if (field.name == "targetPaths") {
                rel.targets = values_.nameListOp(field.rep);
            } else if (field.name == "custom") {
                auto value = values_.value(field.rep);
                rel.isCustom = value && !value->numbers.empty() && value->numbers[0] != 0.0;
            } else if (field.name != "variability" && !kStructuralFields.count(field.name)) {
                addMetadata(rel.metadata, field);
            }
        }
    }

    const crate::File& file_;
    crate::ValueReader values_;
    std::unique_ptr<Layer> layer_;
    SourceLocation where_;
    std::vector<PrimSpec*> containers_;
    std::vector<bool> resolved_;
    std::map<PrimSpec*, std::vector<std::string>> childOrder_;
};

}  // namespace

std::unique_ptr<Layer> readCrateLayer(std::span<const char> bytes, const std::string& identifier) {
    const crate::File file(bytes);
    return LayerBuilder(file, identifier).build();
}

}  // namespace obscura::usda
