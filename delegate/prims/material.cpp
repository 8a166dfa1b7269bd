#include "delegate/prims/material.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::delegate {

void Material::pull(SceneAccess& s, ObscuraDirtyBits, SyncContext& ctx) {
    if (!s.anyDirty()) return;
    auto diffuse = s.getFloat3("inputs:diffuseColor");
    auto emissive = s.getFloat3("inputs:emissiveColor");
    float roughness = std::clamp(s.getFloat("inputs:roughness"), 0.0f, 1.0f);
    float metallic = std::clamp(s.getFloat("inputs:metallic"), 0.0f, 1.0f);
    float opacity = std::clamp(s.getFloat("inputs:opacity"), 0.0f, 1.0f);
    float opacityThreshold = std::clamp(s.getFloat("inputs:opacityThreshold"), 0.0f, 1.0f);
    data_.diffuseRoughness = {diffuse[0], diffuse[1], diffuse[2], roughness};
    diffusePrimvar_ = s.getToken("obscura:diffuseColor:primvar");
    data_.emissiveMetallic = {emissive[0], emissive[1], emissive[2], metallic};
    // UsdPreviewSurface: occlusion is a fraction of the ambient light; outside [0, 1] it has no meaning.
    float occlusion = s.getFloat("inputs:occlusion");
    if (!(occlusion >= 0.0f && occlusion <= 1.0f))
        throw PrimDataError(s.path() + ": inputs:occlusion must be in [0, 1]");
    // An opacity read from a primvar replaces the authored one (the prim's, in its vertices).
    opacityPrimvar_ = s.getToken("obscura:opacity:primvar");
    data_.opacity = {opacityPrimvar_.empty() ? opacity : 1.0f, opacityThreshold, occlusion, 0.0f};
    auto specular = s.getFloat3("inputs:specularColor");
    float ior = s.getFloat("inputs:ior");
    if (!(ior >= 1.0f)) throw PrimDataError(s.path() + ": inputs:ior must be at least 1");
    data_.specularIor = {specular[0], specular[1], specular[2], ior};
    data_.clearcoat = {std::clamp(s.getFloat("inputs:clearcoat"), 0.0f, 1.0f),
                       std::clamp(s.getFloat("inputs:clearcoatRoughness"), 0.0f, 1.0f),
                       s.getInt("inputs:useSpecularWorkflow") != 0 ? 1.0f : 0.0f, 0.0f};
    float anisotropy = s.getFloat("inputs:obscura:anisotropy");
    if (!(anisotropy >= 0.0f && anisotropy <= 1.0f))
        throw PrimDataError(s.path() + ": inputs:obscura:anisotropy must be in [0, 1]");
    float rotationDegrees = s.getFloat("inputs:obscura:anisotropyRotation");
    if (!std::isfinite(rotationDegrees))
        throw PrimDataError(s.path() + ": inputs:obscura:anisotropyRotation must be a finite angle");
    data_.anisotropy = {anisotropy, rotationDegrees * std::numbers::pi_v<float> / 180.0f, 0.0f, 0.0f};
    readTextures(s, ctx);
}

// UsdUVTexture networks the host flattened into obscura:<input>:* (UsdPreviewSurface spec).
void Material::readTextures(SceneAccess& s, SyncContext& ctx) {
    warnings_.clear();
    const char* const sampled[passes::kMaterialTextureSlots] = {"diffuseColor", "roughness", "metallic", "opacity",
                                                                "normal",       "occlusion", "emissiveColor"};
    const BoundTexture* first = nullptr;
    for (uint32_t slot = 0; slot < passes::kMaterialTextureSlots; ++slot) {
        textures_[slot] = readBoundTexture(s, ctx.textures, sampled[slot], warnings_);
        data_.textures[slot] = textures_[slot] ? textures_[slot]->params : passes::MaterialTexture{};
        if (!textures_[slot]) continue;
        if (!first) first = &*textures_[slot];
        else if (textures_[slot]->stPrimvar != first->stPrimvar)
            warnings_.push_back("inputs:" + std::string(sampled[slot]) + " reads primvar '" +
                                textures_[slot]->stPrimvar + "' and another input '" + first->stPrimvar +
                                "': meshes carry one set of texture coordinates (primvars:st), used by all");
    }
    // A textured emissiveColor is sampled by the G-buffer pass into its emission target; the
    // constant keeps the texture's average colour (its 1x1 mip), which the accumulation's
    // pre-exposure takes for the material's brightness.
    if (const auto& emissive = textures_[passes::kTextureEmissive]) {
        std::array<float, 3> average = averageColor(*emissive);
        std::copy(average.begin(), average.end(), data_.emissiveMetallic.begin());
    }
}

}  // namespace obscura::delegate
