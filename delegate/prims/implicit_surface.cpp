#include "delegate/prims/implicit_surface.h"

#include <map>

namespace obscura::delegate {

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
    markDirty(kDirtyTessellation);
    return true;
}

void ImplicitSurface::pull(SceneAccess& s, ObscuraDirtyBits, SyncContext& ctx) {
    pullGprim(s, ctx);
    // The shape: the type's own attributes (size, radius, height, axis...) and the orientation.
    if (s.anyDirtyBut({"transform", "visibility", "purpose", "doubleSided", "material:binding",
                       "primvars:displayColor", "primvars:displayOpacity"})) {
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
    if (s.anyDirty({"primvars:displayColor", "primvars:displayOpacity"})) {
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
    setGeometry(std::move(geometry), ctx, s.path());
}

std::vector<DetailSphere> ImplicitSurface::detailSpheres() const {
    const Aabb bounds = implicitShapeBounds(shape_);
    const double radius = 0.5 * length({bounds.max[0] - bounds.min[0], bounds.max[1] - bounds.min[1],
                                        bounds.max[2] - bounds.min[2]});
    return {{bounds.centre(), radius}};
}

bool ImplicitSurface::chooseDetail(double pixelsPerUnit) {
    const double radiusPixels = implicitCurvatureRadius(shape_) * pixelsPerUnit;
    return setLevel(chooseImplicitLevel(wantedImplicitLevel(radiusPixels, kMaxChordErrorPixels), level_));
}

}  // namespace obscura::delegate
