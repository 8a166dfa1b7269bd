// Meshes whose polygons the delegate makes at a density that follows their size on screen: the
// implicit gprims and curves. After each sync, every such prim is told how many pixels an
// object-space unit covers where it is nearest the camera (over its own placement or each
// instance of it), chooses its density from that with hysteresis (implicit_tessellation.h's
// levels), and is tessellated again only when the density changed.
#pragma once

#include "delegate/prims/mesh.h"

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <vector>

namespace obscura::delegate {

class Camera;

// Chords within a quarter pixel of the silhouette: below what 16 temporal-AA samples resolve.
constexpr double kMaxChordErrorPixels = 0.25;

// No prim is tessellated into more triangles than this (a curve set seen close asks for far more):
// beyond it a finer level is refused with a warning, and a prim that exceeds it
// even at its coarsest is skipped (as a point cloud of over 666,666 points, 12 triangles each).
constexpr uint64_t kMaxTessellatedTriangles = 8'000'000;

// The finest level from `level` down to `coarsest` whose triangle count is within the cap; the
// warning ("", or why it was coarsened) names the counts. Throws PrimDataError (with `path`)
// when even the coarsest is over the cap.
struct CappedLevel {
    int level;
    std::string warning;
};
CappedLevel capTessellation(int level, int coarsest, const std::function<uint64_t(int)>& trianglesAt,
                            const std::string& path);

struct DetailSphere {
    std::array<double, 3> centre;  // object space
    double radius;
};

class ViewDependentMesh : public Mesh {
public:
    using Mesh::Mesh;
    // Object-space spheres covering the prim; the one nearest the eye decides its density.
    virtual std::vector<DetailSphere> detailSpheres() const = 0;
    // Chooses the density for `pixelsPerUnit` screen pixels per object-space unit; true (and the
    // prim marked dirty) when it changed.
    virtual bool chooseDetail(double pixelsPerUnit) = 0;
};

// The most pixels an object-space unit of `spheres` covers over the `placements` (model
// matrices) seen from `eye`: `pixelsPerUnit` (the projection's vertical scale times half the
// viewport's height) over the distance to the nearest sphere's surface for a perspective camera,
// times the placement's largest axis scale; infinity with the eye inside a sphere.
double projectedScale(const std::vector<DetailSphere>& spheres, const std::vector<Matrix4d>& placements,
                      const Vec3d& eye, bool orthographic, double pixelsPerUnit);

// Lets every view-dependent mesh choose its density from the camera's view at a viewport
// `width` x `height` pixels, and returns those whose density changed (to be synced again). Prims
// that are skipped or not yet synced are left alone.
std::vector<ViewDependentMesh*> chooseViewDependentDetail(const std::map<std::string, std::unique_ptr<Prim>>& prims,
                                                          const Camera& camera, uint32_t width, uint32_t height);

// The drawn positions of `tessellate(input)` with the input's points moved to each of the
// shutter's ends (Mesh::pullShutterPoints), or nullopt for a prim that does not deform.
template <typename Input, typename Tessellate>
std::optional<std::array<std::vector<float>, 2>> shutterEnds(const std::optional<std::array<std::vector<float>, 2>>& points,
                                                             Input input, const Tessellate& tessellate) {
    if (!points) return std::nullopt;
    std::array<std::vector<float>, 2> ends;
    for (size_t end = 0; end < 2; ++end) {
        input.points = (*points)[end];
        ends[end] = positionsOf(tessellate(input));
    }
    return ends;
}

}  // namespace obscura::delegate
