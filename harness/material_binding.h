// UsdShade material resolution (UsdShadeMaterialBindingAPI, "Bound Material Resolution"): direct
// bindings (material:binding, material:binding:<purpose>) and collection-based ones
// (material:binding:collection:[<purpose>:]<name>, whose two targets are a UsdCollectionAPI
// collection and a Material). Bindings are inherited down namespace, a descendant's binding
// stronger unless an ancestor's says bindMaterialAs = "strongerThanDescendants"; on one prim the
// collection bindings, in property order, come before the direct one, and a collection binds only
// its members at or beneath the prim that holds it; a purpose's own binding is preferred to an
// all-purpose one.
//
// Obscura renders the "full" purpose (the truest representation, as final-frame renderers do).
// Where the material that purpose resolves has no surface Obscura draws (a renderer-specific
// shader, where a UsdPreviewSurface or MaterialX surface would be drawn) and the "preview"
// purpose resolves one that has, the preview material is drawn: production assets bind such
// viewport stand-ins for preview alone.
#pragma once

#include "harness/usda/stage.h"

#include <functional>
#include <optional>
#include <string>

namespace obscura::harness {

// Whether Obscura draws the surface of the Material at a path.
using DrawableMaterial = std::function<bool(const std::string& materialPath)>;

// The Material bound to `prim`, from its bindings and its ancestors' (or, with `ancestors` false,
// from its own alone: a GeomSubset's). nullopt where nothing binds one.
std::optional<std::string> resolveBoundMaterial(const usda::Stage& stage, const usda::Prim& prim,
                                                const DrawableMaterial& drawable, bool ancestors = true);

// UsdCollectionAPI membership of the prim at `primPath` in the collection at `collectionPath`
// ("/Owner.collection:name"): of its includes and excludes, the most specific path at or above
// the prim decides (expansionRule expandPrims and expandPrimsAndProperties; explicitOnly: only
// the paths themselves); an included collection contributes its members; includeRoot includes
// every prim no path decides. A collection in expression mode (its `mode` "expression", or
// "automatic", the fallback, with no includes, excludes or includeRoot) holds the prims its
// membershipExpression matches (usda/path_expression.h).
bool collectionIncludes(const usda::Stage& stage, const std::string& collectionPath, const std::string& primPath);

}  // namespace obscura::harness
