// USD's instancing key: instanceable prims whose indexes hold the same composition arcs (the same
// sites, reached the same ways, with the same variant selections) compose the same descendants,
// so they can share one prototype (UsdStage's native instancing, Pcp's instance key).
#pragma once

#include <string>

#include "harness/usda/prim_index.h"

namespace obscura::usda {

// The key of the prim whose index is `root`: every arc below the root, in strength order, as
// text; "" when the prim has no arcs (USD instances only prims that composition brings in).
std::string instancingKey(const IndexNode& root);

}  // namespace obscura::usda
