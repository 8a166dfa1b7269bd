#include "delegate/prims/material.h"

#include <algorithm>

namespace obscura::delegate {

void Material::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext&) {
    if (!(bits & OBSCURA_DIRTY_PARAMS)) return;
    auto diffuse = s.getFloat3("inputs:diffuseColor");
    auto emissive = s.getFloat3("inputs:emissiveColor");
    float roughness = std::clamp(s.getFloat("inputs:roughness"), 0.0f, 1.0f);
    float metallic = std::clamp(s.getFloat("inputs:metallic"), 0.0f, 1.0f);
    float opacity = std::clamp(s.getFloat("inputs:opacity"), 0.0f, 1.0f);
    data_.diffuseRoughness = {diffuse[0], diffuse[1], diffuse[2], roughness};
    data_.emissiveMetallic = {emissive[0], emissive[1], emissive[2], metallic};
    data_.opacityPad = {opacity, 0.0f, 0.0f, 0.0f};
}

}  // namespace obscura::delegate
