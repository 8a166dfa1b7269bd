// The NurbsPatch rprim: a mesh whose polygons the delegate evaluates from the rational B-spline
// surface (nurbs_tessellation.h), with steps per knot span chosen from its size on screen
// (view_dependent_mesh.h). Everything else — the transform over the shutter, deformation within
// it, instancing through PointInstancer prototypes, materials — is the mesh's.
#pragma once

#include "delegate/nurbs_tessellation.h"
#include "delegate/prims/view_dependent_mesh.h"

namespace obscura::delegate {

class NurbsPatch final : public ViewDependentMesh {
public:
    using ViewDependentMesh::ViewDependentMesh;
    // A sphere around each knot span's control points (the span lies in their convex hull).
    std::vector<DetailSphere> detailSpheres() const override;
    // Steps per span, each way, keep the surface within kMaxChordErrorPixels of its polygons and
    // resolve its trim loops.
    bool chooseDetail(double pixelsPerUnit) override;
    // Steps per drawn knot span (u, v) of the last tessellation.
    std::array<int, 2> steps() const { return steps_; }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    NurbsPatchInput input_;
    std::array<double, 2> bend_{};  // nurbsBendMagnitude of input_
    std::optional<std::array<std::vector<float>, 2>> shutterPoints_;
    std::array<int, 2> levels_{-1, -1};  // -1: not chosen yet
    std::array<int, 2> steps_{0, 0};
    std::array<int, 2> trimSteps_{1, 1};  // nurbsTrimSteps of input_: the fewest steps per span
};

}  // namespace obscura::delegate
