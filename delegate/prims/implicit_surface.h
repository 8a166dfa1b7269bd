// The implicit gprims (UsdGeomCube, Sphere, Cylinder, Cylinder_1, Cone, Capsule, Capsule_1,
// Plane): meshes whose polygons the delegate tessellates from the shape's parameters
// (implicit_tessellation.h), at a level chosen from their size on screen (view_dependent_mesh.h).
// Everything else — the transform over the shutter, instancing through PointInstancer prototypes,
// materials, displayColor — is the mesh's.
#pragma once

#include "delegate/implicit_tessellation.h"
#include "delegate/prims/view_dependent_mesh.h"

namespace obscura::delegate {

class ImplicitSurface final : public ViewDependentMesh {
public:
    ImplicitSurface(std::string path, const schema::PrimSchema& schema, int32_t primId, ImplicitKind kind)
        : ViewDependentMesh(std::move(path), schema, primId) {
        shape_.kind = kind;
    }
    // The prim type tokens of the implicit gprims ("cube", "cylinder1"...), or nullopt.
    static std::optional<ImplicitKind> kindOf(const std::string& type);

    const ImplicitShape& shape() const { return shape_; }
    // The tessellation level drawn (-1 before the first choice); setting another one marks the
    // prim for re-tessellation.
    int level() const { return level_; }
    bool setLevel(int level);
    // The bounding sphere; the level keeps the chords of the largest curvature radius within a
    // quarter pixel of the silhouette.
    std::vector<DetailSphere> detailSpheres() const override;
    bool chooseDetail(double pixelsPerUnit) override;

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    ImplicitShape shape_;
    bool leftHanded_ = false;
    std::optional<MeshPrimvar> displayColor_;
    std::string colorWarning_;
    int level_ = -1;
};

}  // namespace obscura::delegate
