// The instancer rprim (UsdGeomPointInstancer): per-instance transforms of its prototype meshes,
// drawn with GPU instancing — the meshes stay in memory once.
#pragma once

#include "delegate/mesh_builder.h"
#include "delegate/prims/prim.h"

#include <array>
#include <optional>
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
    // The index in the instancer's arrays (positions, protoIndices...) of instance `k` of prototype
    // `index`: the instanceId AOV (invisible instances are skipped in instancesOf, not here).
    int32_t instanceIndexOf(size_t index, size_t k) const { return indicesByPrototype_.at(index).at(k); }
    // Whether the placements move within the camera's shutter (the instancer's transform, or
    // positions, orientations or scales sampled at the shutter's ends differ).
    bool movesWithinShutter() const { return shutterPlacements_.has_value(); }
    // Instance `k` of prototype `index` at an absolute time within the shutter: between its
    // placements at the shutter's ends, linearly (exactly them at the ends); the frame's placement
    // when the instancer holds still.
    Matrix4d instanceAt(size_t index, size_t k, double time) const;
    bool visible() const { return visible_; }
    size_t instanceCount() const { return protoIndices_.size(); }
    // What its primvars:displayColor and displayOpacity give instance `k` of prototype `index`,
    // overriding its prototype meshes' own (Hydra's instance primvars): one element per instance
    // (vertex or varying interpolation) or one for all (constant); unset where not authored.
    struct InstanceDisplay {
        std::optional<std::array<float, 3>> color;
        std::optional<float> opacity;
    };
    InstanceDisplay displayOf(size_t index, size_t k) const;
    // Some instance's displayOpacity is below 1.
    bool hasTranslucentInstances() const;
    // Primvars of a count that fits neither (ignored), each message naming the instancer.
    const std::vector<std::string>& warnings() const { return warnings_; }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    void reset() override;
    using Placements = std::vector<std::vector<Matrix4d>>;  // by prototype, the visible instances
    struct PointArrays {
        std::vector<float> positions, orientations, scales;
    };
    // The visible instances' placements (indicesByPrototype_), by prototype.
    Placements placementsOf(const PointArrays& points, const Matrix4d& transform, const std::string& path) const;
    // The visible instances' indices by prototype; a prototype index out of range is bad prim data.
    std::vector<std::vector<int32_t>> visibleByPrototype(const std::string& path) const;

    Matrix4d transform_ = kIdentity;
    std::vector<TransformSample> shutterTransforms_;
    std::array<double, 2> shutter_{};
    std::optional<std::array<PointArrays, 2>> shutterPoints_;  // at the shutter's ends, when they differ
    std::optional<std::array<Placements, 2>> shutterPlacements_;
    std::vector<std::string> prototypes_;
    std::vector<int32_t> protoIndices_;
    PointArrays points_;
    std::vector<int32_t> invisible_;
    bool visible_ = true;
    std::vector<std::vector<Matrix4d>> byPrototype_;
    std::vector<std::vector<int32_t>> indicesByPrototype_;  // parallel to byPrototype_
    std::optional<MeshPrimvar> displayColor_, displayOpacity_;
    std::vector<std::string> warnings_;
};

// Orientations (w, x, y, z per instance) followed by the turn of their angular velocities (xyz per
// instance, the axis scaled to degrees per second) over `seconds`, as UsdGeomPointInstancer
// composes them (the orientation's rotation, then the angular velocity's).
std::vector<float> turnOrientations(const std::vector<float>& orientations, const std::vector<float>& angularVelocities,
                                    double seconds);

// USD's instance transform: scale, then rotate by the unit quaternion (w, x, y, z), then
// translate, in the row-vector convention (UsdGeomPointInstancer::ComputeInstanceTransformsAtTime).
Matrix4d instanceTransform(const float* position, const float* orientation, const float* scale);

}  // namespace obscura::delegate
