// A Mesh's GeomSubset children of the materialBind family (UsdShadeMaterialBindingAPI's
// GetMaterialBindSubsets) as the mesh schema's materialSubsets:* attributes carry them: the
// subsets are part of their mesh, as in Hydra's HdMeshTopology, not prims of their own.
#pragma once

#include "harness/usda/stage.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace obscura::harness {

struct MaterialBindSubsets {
    std::vector<int32_t> faceCounts;   // indices of each subset
    std::vector<int32_t> faceIndices;  // every subset's indices, one subset's after another
    std::vector<std::string> materials;  // each subset's bound material
    std::vector<std::string> paths;      // each subset's prim
    bool animated = false;               // some subset's indices are time-sampled

    bool empty() const { return paths.empty(); }
    bool operator==(const MaterialBindSubsets&) const = default;
};

// The subsets of `mesh` at `time`: active GeomSubset children with familyName materialBind,
// elementType face (the schema's fallback) and a binding of their own (`ownBinding`: the material
// its own bindings resolve, material_binding.h). A subset without one binds what its mesh
// resolves to, so it changes nothing and is left out.
MaterialBindSubsets materialBindSubsets(const usda::Prim& mesh, double time,
                                        const std::function<std::optional<std::string>(const usda::Prim&)>& ownBinding);

}  // namespace obscura::harness
