// The implicit gprims (UsdGeomCube, Sphere, Cylinder, Cylinder_1, Cone, Capsule, Capsule_1,
// Plane): meshes whose polygons the delegate tessellates from the shape's parameters
// (implicit_tessellation.h), at a level chosen from their size on screen. Everything else — the
// transform over the shutter, instancing through PointInstancer prototypes, materials,
// displayColor — is the mesh's.
#pragma once

#include "delegate/implicit_tessellation.h"
#include "delegate/prims/mesh.h"

#include <map>
#include <memory>
#include <vector>

namespace obscura::delegate {

class Camera;

class ImplicitSurface final : public Mesh {
public:
    ImplicitSurface(std::string path, const schema::PrimSchema& schema, int32_t primId, ImplicitKind kind)
        : Mesh(std::move(path), schema, primId) {
        shape_.kind = kind;
    }
    // The prim type tokens of the implicit gprims ("cube", "cylinder1"...), or nullopt.
    static std::optional<ImplicitKind> kindOf(const std::string& type);

    const ImplicitShape& shape() const { return shape_; }
    // The tessellation level drawn (-1 before the first choice); setting another one marks the
    // prim for re-tessellation.
    int level() const { return level_; }
    bool setLevel(int level);

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    ImplicitShape shape_;
    bool leftHanded_ = false;
    std::optional<MeshPrimvar> displayColor_;
    std::string colorWarning_;
    int level_ = -1;
};

// The largest radius in pixels that `surface`'s curvature radius has on screen, over the places
// it is drawn: its own transform, or each visible instance of the instancers it is a prototype
// of. `pixelsPerUnit` is the projection's vertical scale times half the viewport's height (at unit
// distance for a perspective camera, everywhere for an orthographic one).
double projectedCurvatureRadius(const ImplicitSurface& surface, const std::vector<Matrix4d>& placements,
                                const Vec3d& eye, bool orthographic, double pixelsPerUnit);

// Chooses every implicit surface's level from the camera's view at a viewport `height` pixels
// high (`width` wide), and returns the surfaces whose level changed (to be synced again). Surfaces that are
// skipped or not yet synced are left alone.
std::vector<ImplicitSurface*> chooseImplicitLevels(const std::map<std::string, std::unique_ptr<Prim>>& prims,
                                                   const Camera& camera, uint32_t width, uint32_t height);

}  // namespace obscura::delegate
