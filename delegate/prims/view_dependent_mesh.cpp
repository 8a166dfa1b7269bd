#include "delegate/prims/view_dependent_mesh.h"

#include "delegate/prims/camera.h"
#include "delegate/prims/instancer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace obscura::delegate {
namespace {

double maxAxisScale(const Matrix4d& m) {
    double scale = 0.0;
    for (int row = 0; row < 3; ++row) scale = std::max(scale, length({m[row * 4], m[row * 4 + 1], m[row * 4 + 2]}));
    return scale;
}

}  // namespace

CappedLevel capTessellation(int level, int coarsest, const std::function<uint64_t(int)>& trianglesAt,
                            const std::string& path) {
    const uint64_t wanted = trianglesAt(level);
    int capped = level;
    while (capped > coarsest && trianglesAt(capped) > kMaxTessellatedTriangles) --capped;
    const uint64_t drawn = trianglesAt(capped);
    if (drawn > kMaxTessellatedTriangles)
        throw PrimDataError(path + ": " + std::to_string(drawn) + " triangles at the coarsest tessellation, more than the " +
                            std::to_string(kMaxTessellatedTriangles) + " a prim may have; split it into smaller prims");
    if (capped == level) return {level, {}};
    return {capped, "tessellation capped at " + std::to_string(kMaxTessellatedTriangles) + " triangles per prim: the " +
                        std::to_string(wanted) + " its size on screen asks for were cut to " + std::to_string(drawn) +
                        " (drawn coarser)"};
}

double projectedScale(const std::vector<DetailSphere>& spheres, const std::vector<Matrix4d>& placements,
                      const Vec3d& eye, bool orthographic, double pixelsPerUnit) {
    double widest = 0.0;
    for (const Matrix4d& model : placements) {
        const double scale = maxAxisScale(model);
        if (orthographic) {
            widest = std::max(widest, scale * pixelsPerUnit);
            continue;
        }
        // Perspective: the scale at the nearest point of the nearest sphere (a long cylinder's
        // near end decides); an eye inside one needs the finest level.
        double nearest = std::numeric_limits<double>::infinity();
        for (const DetailSphere& sphere : spheres) {
            const Vec3d centre = transformPoint(sphere.centre, model);
            nearest = std::min(nearest, length({centre[0] - eye[0], centre[1] - eye[1], centre[2] - eye[2]}) -
                                            sphere.radius * scale);
        }
        if (!(nearest > 0.0)) return std::numeric_limits<double>::infinity();
        widest = std::max(widest, scale / nearest * pixelsPerUnit);
    }
    return widest;
}

std::vector<ViewDependentMesh*> chooseViewDependentDetail(const std::map<std::string, std::unique_ptr<Prim>>& prims,
                                                          const Camera& camera, uint32_t width, uint32_t height) {
    std::vector<const Instancer*> instancers;
    for (const auto& [path, prim] : prims)
        if (auto* instancer = dynamic_cast<const Instancer*>(prim.get()); instancer && !instancer->skipped())
            instancers.push_back(instancer);
    const Matrix4d& cameraToWorld = camera.params().cameraToWorld;
    const Vec3d eye{cameraToWorld[12], cameraToWorld[13], cameraToWorld[14]};
    const Matrix4d projection = camera.projectionMatrix(height > 0 ? double(width) / double(height) : 1.0);
    const double pixelsPerUnit = std::abs(projection[5]) * 0.5 * double(height);
    std::vector<ViewDependentMesh*> changed;
    for (const auto& [path, prim] : prims) {
        auto* mesh = dynamic_cast<ViewDependentMesh*>(prim.get());
        if (!mesh || mesh->skipped() || mesh->dirtyBits() != OBSCURA_DIRTY_CLEAN) continue;
        // Drawn at its own transform, or (a prototype) at every instance of it.
        std::vector<Matrix4d> placements;
        bool prototype = false;
        for (const Instancer* instancer : instancers)
            if (int index = instancer->prototypeOf(path); index >= 0) {
                prototype = true;
                for (const Matrix4d& instance : instancer->instancesOf(size_t(index)))
                    placements.push_back(multiply(mesh->transform(), instance));
            }
        if (!prototype) placements.push_back(mesh->transform());
        double scale = projectedScale(mesh->detailSpheres(), placements, eye, camera.params().orthographic, pixelsPerUnit);
        if (mesh->chooseDetail(scale)) changed.push_back(mesh);
    }
    return changed;
}

}  // namespace obscura::delegate
