#include "passes/frame_data.h"

#include <cmath>

namespace obscura::passes {

uint32_t materialFeatures(const MaterialData& material) {
    uint32_t features = material.anisotropy[0] > 0.0f ? kMaterialAnisotropic : 0u;
    for (uint32_t slot = 0; slot < kMaterialTextureSlots; ++slot) {
        const MaterialTexture& t = material.textures[slot];
        if (t.sampled == 0) continue;
        features |= kMaterialTextured;
        if (t.udimGrid[2] > 0.0f) features |= kMaterialUdim;
        if (t.transformed != 0) features |= kMaterialTransformedTexture;
        if (slot == kTextureNormal) features |= kMaterialNormalMap;
        if (slot == kTextureEmissive) features |= kMaterialTexturedEmission;
    }
    return features;
}

uint32_t lightKind(const LightData& light) {
    const auto type = LightType(uint32_t(light.positionType[3]));
    uint32_t kind = 1u << uint32_t(type);
    if (light.shadow[1] > 0) kind |= 1u << (8 + light.shadow[2]);
    // light_evaluation.glsl shapingAttenuation, which local lights take: a cone narrower than a
    // hemisphere, or a focus.
    const bool local = type != LightType::Distant && type != LightType::Dome;
    if (local && (light.shaping[0] < 0.5f * float(M_PI) || light.shaping[2] > 0.0f)) kind |= kLightKindShaped;
    // LightData::factors z: the dome lighting through the environment maps.
    if (type == LightType::Dome && light.factors[2] > 0.5f) kind |= kLightKindTexturedDome;
    return kind;
}

}  // namespace obscura::passes
