// UsdGeomPrimvarsAPI's primvar inheritance: a constant primvar with an authored value applies to
// every descendant that does not author one of its name (FindInheritablePrimvars,
// FindPrimvarWithInheritance).
#include "harness/usda/stage.h"

namespace obscura::usda {

namespace {

constexpr std::string_view kPrimvarPrefix = "primvars:";
constexpr std::string_view kIndicesSuffix = ":indices";

// A primvar's name is in the primvars: namespace; its :indices companion is no primvar.
bool isPrimvar(const std::string& name) {
    return name.starts_with(kPrimvarPrefix) && !name.ends_with(kIndicesSuffix);
}

// Fallback values are not inherited, nor blocked ones (composition leaves those valueless).
bool hasAuthoredValue(const Attribute& attribute) {
    return attribute.defaultValue.has_value() || !attribute.timeSamples.empty() || attribute.spline;
}

// A primvar without interpolation metadata is constant (UsdGeomPrimvar::GetInterpolation).
bool isConstant(const Attribute& attribute) {
    const auto it = attribute.metadata.find("interpolation");
    return it == attribute.metadata.end() || it->second.strings.empty() || it->second.strings.front() == "constant";
}

}  // namespace

std::map<std::string, const Attribute*> Stage::inheritablePrimvars(const Prim& prim) const {
    // Nearest first: a prim's primvar replaces its ancestors' of the same name, and one of
    // another interpolation stops theirs.
    std::map<std::string, const Attribute*> nearest;
    for (const Prim* p = &prim; p; p = p->parent)
        for (const auto& [name, attribute] : p->attributes)
            if (isPrimvar(name) && hasAuthoredValue(attribute))
                nearest.emplace(name, isConstant(attribute) ? &attribute : nullptr);
    std::erase_if(nearest, [](const auto& entry) { return entry.second == nullptr; });
    return nearest;
}

const Attribute* Stage::primvar(const Prim& prim, const std::string& name) const {
    for (const Prim* p = &prim; p; p = p->parent) {
        const Attribute* attribute = p->attribute(name);
        if (!attribute || !hasAuthoredValue(*attribute)) continue;
        return p == &prim || isConstant(*attribute) ? attribute : nullptr;
    }
    return nullptr;
}

const Prim& Stage::primAuthoring(const Prim& prim, const Attribute& attribute) const {
    for (const Prim* p = &prim; p; p = p->parent)
        if (p->attribute(attribute.name) == &attribute) return *p;
    return prim;
}

}  // namespace obscura::usda
