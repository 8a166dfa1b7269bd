// The instancer rprim (UsdGeomPointInstancer): per-instance transforms of its prototype meshes,
// drawn with GPU instancing — the meshes stay in memory once.
#pragma once

#include "delegate/prims/prim.h"

#include <string>
#include <vector>

namespace obscura::delegate {

class Instancer final : public Prim {
public:
    using Prim::Prim;

    // Prototype roots in protoIndices order; a mesh at or below a root belongs to that prototype.
    const std::vector<std::string>& prototypes() const { return prototypes_; }
    // The prototype index of `meshPath`, or -1 when the mesh is not one of this instancer's.
    int prototypeOf(const std::string& meshPath) const;
    // Instance-to-world matrices (instance transform, then the instancer's transform) of the
    // visible instances of prototype `index`.
    const std::vector<Matrix4d>& instancesOf(size_t index) const { return byPrototype_.at(index); }
    bool visible() const { return visible_; }
    size_t instanceCount() const { return protoIndices_.size(); }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    void reset() override;
    void rebuildInstances(const std::string& path);

    Matrix4d transform_ = kIdentity;
    std::vector<std::string> prototypes_;
    std::vector<int32_t> protoIndices_;
    std::vector<float> positions_, orientations_, scales_;
    std::vector<int32_t> invisible_;
    bool visible_ = true;
    std::vector<std::vector<Matrix4d>> byPrototype_;
};

// USD's instance transform: scale, then rotate by the unit quaternion (w, x, y, z), then
// translate, in the row-vector convention (UsdGeomPointInstancer::ComputeInstanceTransformsAtTime).
Matrix4d instanceTransform(const float* position, const float* orientation, const float* scale);

}  // namespace obscura::delegate
