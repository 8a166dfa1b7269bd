// The mesh rprim: topology, points and primvars pulled from the host, triangulated on the CPU
// and uploaded as one vertex and one index buffer. Implicit surfaces (prims/implicit_surface.h)
// are meshes whose polygons the delegate makes; they share everything drawn from here on.
#pragma once

#include "delegate/bounds.h"
#include "delegate/geometry_cache.h"
#include "delegate/material_subsets.h"
#include "delegate/mesh_builder.h"
#include "delegate/purposes.h"
#include "delegate/prims/prim.h"
#include "delegate/subdivision.h"
#include "gpu/device.h"

namespace obscura::delegate {

// A run of a mesh's indices drawn with one material: the faces of one material subset, or those
// in none (the mesh's own binding).
struct MaterialPart {
    std::optional<std::string> material;  // the bound material's path; none: the fallback material
    IndexRange indices;
    std::string subset;  // the material subset it draws, as messages name it (subsetSubject); "" for the mesh's own faces
};

// Primvar `name` with its interpolation, `components` values per element; nullopt when not authored.
std::optional<MeshPrimvar> pullPrimvar(SceneAccess& scene, const char* name, size_t components);

class Mesh : public Prim {
public:
    Mesh(std::string path, const schema::PrimSchema& schema, int32_t primId)
        : Prim(std::move(path), schema), primId_(primId) {}

    int32_t primId() const { return primId_; }
    bool drawable() const { return visible_ && hasGeometry(); }
    // The computed purpose (purposes.h): drawn when the render setting includedPurposes names it.
    uint32_t purpose() const { return purpose_; }
    bool hasGeometry() const { return vertices_ && indexCount_ > 0; }  // drawn or not (clip volumes)
    const gpu::BufferPtr& vertices() const { return vertices_; }
    const gpu::BufferPtr& indices() const { return indices_; }
    uint32_t indexCount() const { return indexCount_; }
    const Aabb& localBounds() const { return localBounds_; }  // of the drawn (refined) points
    const Matrix4d& transform() const { return transform_; }
    // The transform at an absolute time within the camera's shutter, between the samples synced
    // over it; a prim with one sample is static.
    Matrix4d transformAt(double time) const {
        return shutterTransforms_.size() > 1 ? interpolateTransform(shutterTransforms_, time) : transform_;
    }
    // Deforming within the shutter: its drawn vertices at the shutter's open and close
    // (passes::ShutterPositions), else null.
    const gpu::BufferPtr& shutterPositions() const { return shutterPositions_; }
    bool doubleSided() const { return doubleSided_; }
    // Its back faces draw nothing wanted: a single-sided surface's (UsdGeomGprim's doubleSided off).
    virtual bool backFacesUnwanted() const { return !doubleSided_; }
    const std::optional<std::string>& materialPath() const { return material_; }
    // What draws with which material: one part for a mesh without material subsets; parts
    // without triangles left out. Together they are every index of indices().
    const std::vector<MaterialPart>& materialParts() const { return parts_; }
    // Constant primvars:displayOpacity in [0, 1] (1 when not authored or not constant): without a
    // material, below 1 the prim is transparent (Hydra's fallback material reads displayOpacity).
    float displayOpacity() const { return displayOpacity_; }
    // Some drawn vertex's displayOpacity (uniform, vertex or faceVarying, in the vertex alpha) is
    // below 1: without a material the prim is transparent.
    bool hasTranslucentVertices() const { return translucentVertices_; }
    // Its triangles bound spheres the passes ray-cast (passes::Draw::sphereImpostors): points.
    virtual bool drawsSphereImpostors() const { return false; }
    // What its data lacked, each message naming its prim (the mesh, or one of its material subsets).
    const std::vector<std::string>& warnings() const { return warnings_; }

protected:
    void reset() override;
    // Queues reset(): a prim left with nothing to draw keeps nothing from before.
    void dropGeometry(SyncContext& ctx) {
        ctx.onDevice([this] { reset(); });
    }
    // What every gprim pulls: transform samples, visibility and purpose, sidedness, material,
    // display opacity.
    void pullGprim(SceneAccess& scene, SyncContext& ctx);
    // Keeps the drawn polygons' bounds and warnings, and queues their upload (shared through the
    // geometry cache, keyed here on the pulling thread); the vertices and indices are moved out.
    // Returns the number of vertices.
    size_t setGeometry(MeshGeometry&& geometry, SyncContext& ctx, const std::string& path);
    // The same for a mesh built already, maybe shared with other prims (geometry_cache.h).
    size_t useBuiltMesh(std::shared_ptr<BuiltMesh> built, SyncContext& ctx, const std::string& path);
    // `points` at the shutter's open and close when they differ from the frame's (the prim
    // deforms within the shutter: motion blur's velocities), moved by their velocities where those
    // are authored, else the host's samples (point_motion.h); nullopt when they do not move.
    static std::optional<std::array<std::vector<float>, 2>> pullShutterPoints(SceneAccess& scene,
                                                                              const std::vector<float>& points,
                                                                              const SyncContext& ctx);
    // The drawn vertices' positions (xyz each) at the shutter's ends, or nullopt for a prim that
    // does not deform; `vertexCount` is the drawn geometry's. Queues their upload.
    void setShutterPositions(const std::optional<std::array<std::vector<float>, 2>>& ends, size_t vertexCount,
                             SyncContext& ctx, const std::string& path);
    // Non-constant primvars:displayOpacity as pulled; null when constant or not authored.
    std::optional<MeshPrimvar> varyingOpacity_;

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    // materialParts() from the drawn groups and the bindings of the mesh and its subsets.
    void updateMaterialParts();
    // The key of what the drawn mesh is built from (BuiltMeshCache): input_, refined to `level`.
    ContentKey inputKey(int level) const;
    // The drawn (refined, triangulated) vertex positions of the mesh with `points` instead of its own.
    std::vector<float> drawnPositions(const std::vector<float>& points, int level, const std::string& path);

    int32_t primId_;
    MeshInput input_;
    SubdivisionScheme scheme_ = SubdivisionScheme::CatmullClark;
    SubdivisionTags tags_;
    int refineLevelOverride_ = -1;
    SubdivisionCache subdivision_;
    bool pointsAnimated_ = false;  // points changed while the topology stayed (subdivision_ keeps its refiner)
    Matrix4d transform_ = kIdentity;
    std::vector<TransformSample> shutterTransforms_;  // over the shutter: reference sub-frames, motion blur
    bool doubleSided_ = false;
    bool visible_ = true;
    uint32_t purpose_ = kPurposeDefault;
    float displayOpacity_ = 1.0f;
    bool translucentVertices_ = false;
    std::optional<std::string> material_;
    MaterialSubsets subsets_;
    std::vector<std::string> subsetMaterials_;  // materialSubsets:materials
    std::vector<IndexRange> groupRanges_;        // of the drawn indices: the mesh's own faces, then each subset's
    std::vector<MaterialPart> parts_;
    std::shared_ptr<const BuiltMesh> built_;  // what vertices_ and indices_ come from, kept for prims with equal inputs
    gpu::BufferPtr vertices_;
    gpu::BufferPtr indices_;
    std::optional<std::array<std::vector<float>, 2>> shutterPoints_;  // points at the shutter's ends
    gpu::BufferPtr shutterPositions_;
    uint32_t indexCount_ = 0;
    Aabb localBounds_;
    std::vector<std::string> warnings_;
};

}  // namespace obscura::delegate
