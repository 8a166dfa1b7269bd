#include "harness/material_bind_subsets.h"

namespace obscura::harness {
namespace {

std::string tokenOf(const usda::Prim& prim, const char* name, const char* fallback, double time) {
    const usda::Attribute* attribute = prim.attribute(name);
    auto value = attribute ? attribute->evaluate(time) : std::nullopt;
    return value && value->strings.size() == 1 ? value->strings.front() : fallback;
}

}  // namespace

MaterialBindSubsets materialBindSubsets(const usda::Prim& mesh, double time,
                                        const std::function<std::optional<std::string>(const usda::Prim&)>& ownBinding) {
    MaterialBindSubsets subsets;
    for (const auto& child : mesh.children) {
        if (child->typeName != "GeomSubset" || !child->active) continue;
        if (tokenOf(*child, "familyName", "", time) != "materialBind" ||
            tokenOf(*child, "elementType", "face", time) != "face")
            continue;
        const std::optional<std::string> material = ownBinding(*child);
        if (!material) continue;
        const usda::Attribute* indices = child->attribute("indices");
        auto values = indices ? indices->evaluate(time) : std::nullopt;
        subsets.faceCounts.push_back(values ? int32_t(values->numbers.size()) : 0);
        // Indices that are no int32 face index (negative, too large) reach the plugin as such
        // and are reported there with their subset.
        if (values)
            for (double index : values->numbers)
                subsets.faceIndices.push_back(index >= -2147483648.0 && index <= 2147483647.0 ? int32_t(index) : -1);
        subsets.materials.push_back(*material);
        subsets.paths.push_back(child->path);
        subsets.animated = subsets.animated || (indices && indices->isAnimated());
    }
    return subsets;
}

}  // namespace obscura::harness
