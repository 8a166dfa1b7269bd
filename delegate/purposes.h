// UsdGeomImageable's purposes as Hydra's render tags: a prim's computed purpose is one bit, the
// render setting includedPurposes a mask of the bits drawn (HdRenderPassState's render tags).
#pragma once

#include <cstdint>
#include <string_view>

namespace obscura::delegate {

enum PurposeBit : uint32_t {
    kPurposeDefault = 1u << 0,
    kPurposeRender = 1u << 1,
    kPurposeProxy = 1u << 2,
    kPurposeGuide = 1u << 3,
};

// The bit of a purpose token (UsdGeomTokens: default, render, proxy, guide); 0 for anything else.
uint32_t purposeBit(std::string_view token);
// The bits of a comma-separated list of purposes ("default,render"); unknown entries add none.
uint32_t purposeMask(std::string_view list);

}  // namespace obscura::delegate
