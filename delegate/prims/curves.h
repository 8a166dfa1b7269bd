// The BasisCurves and Points rprims: meshes whose triangles the delegate makes from the curves'
// control points and widths (tubes or ribbons, at a density chosen from their size on screen:
// view_dependent_mesh.h) or the points' widths (sphere impostors: a bounding cube per point, which
// the passes ray-cast), through curve_tessellation.h. Everything else — the transform over the
// shutter, deformation within it (velocities or point samples), instancing through PointInstancer
// prototypes, materials — is the mesh's.
#pragma once

#include "delegate/curve_tessellation.h"
#include "delegate/prims/view_dependent_mesh.h"

namespace obscura::delegate {

class Curves final : public ViewDependentMesh {
public:
    using ViewDependentMesh::ViewDependentMesh;
    // Each control point, as wide as the widest curve.
    std::vector<DetailSphere> detailSpheres() const override;
    // Sides around a tube keep its chords within kMaxChordErrorPixels of its silhouette; steps
    // along a cubic segment keep the segment within it of its chords.
    bool chooseDetail(double pixelsPerUnit) override;
    const CurveDetail& detail() const { return detail_; }
    // Tubes are closed and ribbons draw each side as faces of its own, doubleSided or not.
    bool backFacesUnwanted() const override { return true; }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    CurvesInput input_;
    std::optional<std::array<std::vector<float>, 2>> shutterPoints_;
    int sidesLevel_ = -1, stepsLevel_ = -1;  // -1: not chosen yet
    CurveDetail detail_;
};

// Exact spheres at any size on screen, 12 triangles each: no density to choose.
class Points final : public Mesh {
public:
    using Mesh::Mesh;
    bool drawsSphereImpostors() const override { return true; }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    PointsInput input_;
    std::optional<std::array<std::vector<float>, 2>> shutterPoints_;
};

}  // namespace obscura::delegate
