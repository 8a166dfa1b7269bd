// USD's instancing key: instanceable prims whose indexes hold the same composition arcs (the same
// sites, reached the same ways, with the same variant selections) compose the same descendants,
// so they can share one prototype (UsdStage's native instancing, Pcp's instance key).
#pragma once

#include <string>

#include "harness/usda/prim_index.h"

namespace obscura::usda {

// The key of the prim whose index is `root`: the arcs the prim's own sites introduce, with all
// they bring, in strength order, as text (Pcp_TraverseInstanceableStrongToWeak's nodes); arcs
// carried from ancestors, and the prim's own opinions, are not the instance's to share. "" when the
// prim is no instance: `instanceable` does not resolve to true, or those arcs bring no spec (USD
// instances only prims that composition brings content to; instanceable alone is ignored).
std::string instancingKey(const IndexNode& root);

}  // namespace obscura::usda
