#include "delegate/prims/implicit_surface.h"

#include "delegate/prims/camera.h"
#include "delegate/prims/instancer.h"

#include <algorithm>
#include <cmath>

namespace obscura::delegate {
namespace {

// Chords within a quarter pixel of the silhouette: below what 16 temporal-AA samples resolve.
constexpr double kMaxChordErrorPixels = 0.25;

double maxAxisScale(const Matrix4d& m) {
    double scale = 0.0;
    for (int row = 0; row < 3; ++row) scale = std::max(scale, length({m[row * 4], m[row * 4 + 1], m[row * 4 + 2]}));
    return scale;
}

}  // namespace

std::optional<ImplicitKind> ImplicitSurface::kindOf(const std::string& type) {
    static const std::map<std::string, ImplicitKind> kKinds = {
        {"cube", ImplicitKind::Cube},         {"sphere", ImplicitKind::Sphere},      {"cylinder", ImplicitKind::Frustum},
        {"cylinder1", ImplicitKind::Frustum}, {"cone", ImplicitKind::Frustum},       {"capsule", ImplicitKind::Capsule},
        {"capsule1", ImplicitKind::Capsule},  {"plane", ImplicitKind::Plane}};
    auto it = kKinds.find(type);
    return it == kKinds.end() ? std::nullopt : std::optional(it->second);
}

bool ImplicitSurface::setLevel(int level) {
    if (level == level_) return false;
    level_ = level;
    markDirty(OBSCURA_DIRTY_TOPOLOGY);
    return true;
}

void ImplicitSurface::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext& ctx) {
    pullGprim(s, bits, ctx);
    if (bits & (OBSCURA_DIRTY_PARAMS | OBSCURA_DIRTY_TOPOLOGY)) {
        const std::string type = schema().name;
        ImplicitShape shape;
        shape.kind = shape_.kind;
        if (type == "cube") shape.size = s.getDouble("size");
        if (type == "sphere") shape.radiusBottom = s.getDouble("radius");
        if (type == "cylinder" || type == "cone" || type == "capsule") {
            shape.radiusBottom = s.getDouble("radius");
            shape.radiusTop = type == "cone" ? 0.0 : shape.radiusBottom;
        }
        if (type == "cylinder1" || type == "capsule1") {
            shape.radiusBottom = s.getDouble("radiusBottom");
            shape.radiusTop = s.getDouble("radiusTop");
        }
        if (shape.kind == ImplicitKind::Frustum || shape.kind == ImplicitKind::Capsule) shape.height = s.getDouble("height");
        if (shape.kind == ImplicitKind::Plane) {
            shape.width = s.getDouble("width");
            shape.length = s.getDouble("length");
        }
        if (shape.kind != ImplicitKind::Cube && shape.kind != ImplicitKind::Sphere) shape.axis = s.getToken("axis")[0] - 'X';
        if (std::string problem = implicitShapeProblem(shape); !problem.empty()) throw PrimDataError(s.path() + ": " + problem);
        shape_ = shape;
        leftHanded_ = s.getToken("orientation") == "leftHanded";
    }
    if (bits & OBSCURA_DIRTY_PRIMVAR) {
        // The polygons follow the view, so only a constant colour has elements to fit them.
        displayColor_.reset();
        colorWarning_.clear();
        if (auto c = s.getFloatArray("primvars:displayColor")) {
            ObscuraInterpolation interpolation = s.interpolation("primvars:displayColor");
            if (interpolation == OBSCURA_INTERPOLATION_CONSTANT) displayColor_ = MeshPrimvar{std::move(*c), interpolation};
            else
                colorWarning_ = "primvars:displayColor of an implicit surface is used only with constant interpolation "
                                "(its polygons are the delegate's, with no elements of their own to vary over); ignored";
        }
        if (varyingOpacity_)
            colorWarning_ += std::string(colorWarning_.empty() ? "" : "; ") +
                             "primvars:displayOpacity of an implicit surface is used only with constant interpolation; ignored";
    }
    if (level_ < 0) return;  // tessellated once the view is known (chooseImplicitLevels)
    MeshInput input = tessellateImplicitShape(shape_, implicitSegments(level_), leftHanded_);
    input.displayColor = displayColor_;
    auto built = buildMeshGeometry(input);
    if (auto* problem = std::get_if<std::string>(&built)) throw PrimDataError(s.path() + ": " + *problem);
    auto& geometry = std::get<MeshGeometry>(built);
    if (!colorWarning_.empty()) geometry.warnings.push_back(colorWarning_);
    setGeometry(geometry, ctx, s.path());
}

double projectedCurvatureRadius(const ImplicitSurface& surface, const std::vector<Matrix4d>& placements,
                                const Vec3d& eye, bool orthographic, double pixelsPerUnit) {
    const double radius = implicitCurvatureRadius(surface.shape());
    const Aabb bounds = implicitShapeBounds(surface.shape());
    const double boundingRadius = 0.5 * length({bounds.max[0] - bounds.min[0], bounds.max[1] - bounds.min[1],
                                                bounds.max[2] - bounds.min[2]});
    double widest = 0.0;
    for (const Matrix4d& model : placements) {
        const double scale = maxAxisScale(model);
        if (orthographic) {
            widest = std::max(widest, radius * scale * pixelsPerUnit);
            continue;
        }
        // Perspective: the curvature radius seen from the nearest point of the bounding sphere
        // (a long cylinder's near end decides); an eye inside it needs the finest level.
        const Vec3d centre = transformPoint(bounds.centre(), model);
        const double distance = length({centre[0] - eye[0], centre[1] - eye[1], centre[2] - eye[2]}) - boundingRadius * scale;
        if (!(distance > 0.0)) return std::numeric_limits<double>::infinity();
        widest = std::max(widest, radius * scale / distance * pixelsPerUnit);
    }
    return widest;
}

std::vector<ImplicitSurface*> chooseImplicitLevels(const std::map<std::string, std::unique_ptr<Prim>>& prims,
                                                   const Camera& camera, uint32_t width, uint32_t height) {
    std::vector<const Instancer*> instancers;
    for (const auto& [path, prim] : prims)
        if (auto* instancer = dynamic_cast<const Instancer*>(prim.get()); instancer && !instancer->skipped())
            instancers.push_back(instancer);
    const Matrix4d& cameraToWorld = camera.params().cameraToWorld;
    const Vec3d eye{cameraToWorld[12], cameraToWorld[13], cameraToWorld[14]};
    const Matrix4d projection = camera.projectionMatrix(height > 0 ? double(width) / double(height) : 1.0);
    const double pixelsPerUnit = std::abs(projection[5]) * 0.5 * double(height);
    std::vector<ImplicitSurface*> changed;
    for (const auto& [path, prim] : prims) {
        auto* surface = dynamic_cast<ImplicitSurface*>(prim.get());
        if (!surface || surface->skipped() || surface->dirtyBits() != OBSCURA_DIRTY_CLEAN) continue;
        // Drawn at its own transform, or (a prototype) at every instance of it.
        std::vector<Matrix4d> placements;
        bool prototype = false;
        for (const Instancer* instancer : instancers)
            if (int index = instancer->prototypeOf(path); index >= 0) {
                prototype = true;
                for (const Matrix4d& instance : instancer->instancesOf(size_t(index)))
                    placements.push_back(multiply(surface->transform(), instance));
            }
        if (!prototype) placements.push_back(surface->transform());
        double radiusPixels = projectedCurvatureRadius(*surface, placements, eye, camera.params().orthographic, pixelsPerUnit);
        int level = chooseImplicitLevel(wantedImplicitLevel(radiusPixels, kMaxChordErrorPixels), surface->level());
        if (surface->setLevel(level)) changed.push_back(surface);
    }
    return changed;
}

}  // namespace obscura::delegate
