// The material sprim: the UsdPreviewSurface inputs the host flattened from its shading network.
#pragma once

#include "delegate/material_texture.h"
#include "delegate/prims/prim.h"
#include "passes/frame_data.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace obscura::delegate {

class Material final : public Prim {
public:
    using Prim::Prim;
    const passes::MaterialData& data() const { return data_; }
    // Textures of the inputs the G-buffer pass samples, in passes::MaterialTextureSlot order;
    // empty where the input is constant.
    const std::array<std::optional<BoundTexture>, passes::kMaterialTextureSlots>& textures() const { return textures_; }
    const std::vector<std::string>& warnings() const { return warnings_; }
    // The primvar diffuseColor reads (obscura:diffuseColor:primvar): the host serves it as the
    // bound prims' displayColor, their base colour in place of diffuseColor. Empty: none.
    const std::string& diffusePrimvar() const { return diffusePrimvar_; }
    // The same for opacity (obscura:opacity:primvar): served as displayOpacity, the opacity.
    const std::string& opacityPrimvar() const { return opacityPrimvar_; }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    void readTextures(SceneAccess& scene, SyncContext& ctx);
    passes::MaterialData data_{};
    std::array<std::optional<BoundTexture>, passes::kMaterialTextureSlots> textures_;
    std::vector<std::string> warnings_;
    std::string diffusePrimvar_;
    std::string opacityPrimvar_;
};

}  // namespace obscura::delegate
