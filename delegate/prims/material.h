// The material sprim: the UsdPreviewSurface inputs the host flattened from its shading network.
#pragma once

#include "delegate/prims/prim.h"
#include "passes/frame_data.h"

namespace obscura::delegate {

class Material final : public Prim {
public:
    using Prim::Prim;
    const passes::MaterialData& data() const { return data_; }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    passes::MaterialData data_{};
};

}  // namespace obscura::delegate
