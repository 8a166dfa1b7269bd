// Omniverse's OmniPBR MDL material (a Shader with info:implementationSource "sourceAsset",
// info:mdl:sourceAsset OmniPBR.mdl and subIdentifier OmniPBR, or its ClearCoat and Opacity
// variants, on a Material's outputs:mdl:surface), as Omniverse and Isaac content binds it, mapped
// onto Obscura's material model (the inputs of UsdPreviewSurface): its constants with their MDL
// defaults, its textures (asset inputs, read as their colorSpace says or sRGB for colours), the
// OmniPBR formulas folded into scale and bias. What has no place in the model is reported once.
#pragma once

#include "harness/materialx_surface.h"
#include "harness/usda/stage.h"

namespace obscura::harness {

// Whether `shader` is an OmniPBR material this mapping reads.
bool isOmniPbrShader(const usda::Prim& shader);

// `shader`'s inputs at `time`, mapped.
MaterialXMapping mapOmniPbrSurface(const usda::Stage& stage, const usda::Prim& shader, double time);

}  // namespace obscura::harness
