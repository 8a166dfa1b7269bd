#include "delegate/prims/curves.h"

#include "delegate/implicit_tessellation.h"

#include <algorithm>

namespace obscura::delegate {
namespace {

// Whether the tube or sphere geometry needs building again: anything but the placement, visibility
// and binding changed, or the view asks for another density.
bool geometryDirty(const SceneAccess& s, ObscuraDirtyBits bits) {
    return (bits & kDirtyTessellation) ||
           s.anyDirtyBut({"transform", "visibility", "purpose", "doubleSided", "material:binding"});
}

// UsdGeomCurves / UsdGeomPoints: `widths`, else the primvar of the same name.
std::optional<MeshPrimvar> pullWidths(SceneAccess& s) {
    if (auto widths = pullPrimvar(s, "widths", 1)) return widths;
    return pullPrimvar(s, "primvars:widths", 1);
}

CurveBasis basisOf(SceneAccess& s) {
    if (s.getToken("type") == "linear") return CurveBasis::Linear;
    const std::string basis = s.getToken("basis");
    return basis == "bspline" ? CurveBasis::Bspline : basis == "catmullRom" ? CurveBasis::CatmullRom : CurveBasis::Bezier;
}

CurveWrap wrapOf(SceneAccess& s) {
    const std::string wrap = s.getToken("wrap");
    return wrap == "periodic" ? CurveWrap::Periodic : wrap == "pinned" ? CurveWrap::Pinned : CurveWrap::Nonperiodic;
}

// Every point as a sphere of `radius` (or its own).
std::vector<DetailSphere> spheresAt(const std::vector<float>& points, const std::function<double(size_t)>& radius) {
    std::vector<DetailSphere> spheres(points.size() / 3);
    for (size_t i = 0; i < spheres.size(); ++i)
        spheres[i] = {{points[3 * i], points[3 * i + 1], points[3 * i + 2]}, radius(i)};
    return spheres;
}

}  // namespace

std::vector<DetailSphere> Curves::detailSpheres() const {
    const double radius = curveMaxRadius(input_);
    return spheresAt(input_.points, [&](size_t) { return radius; });
}

bool Curves::chooseDetail(double pixelsPerUnit) {
    const int sides = chooseImplicitLevel(wantedImplicitLevel(curveMaxRadius(input_) * pixelsPerUnit, kMaxChordErrorPixels),
                                          sidesLevel_);
    // A cubic segment's second derivative is at most 6 M (curve_tessellation.h).
    const double bendPixels = 6.0 * curveBendMagnitude(input_) * pixelsPerUnit;
    const int steps = chooseImplicitLevel(wantedStepLevel(bendPixels, kMaxChordErrorPixels), stepsLevel_);
    if (sides == sidesLevel_ && steps == stepsLevel_) return false;
    sidesLevel_ = sides;
    stepsLevel_ = steps;
    markDirty(kDirtyTessellation);
    return true;
}

void Curves::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext& ctx) {
    pullGprim(s, ctx);
    if (!geometryDirty(s, bits)) return;
    // Widths and primvars are checked against the topology: read again when it changes.
    const bool topology = s.anyDirty({"curveVertexCounts", "type", "basis", "wrap"});
    if (topology || s.anyDirty({"points", "velocities", "accelerations", "widths"})) {
        input_.points = s.getFloatArray("points").value_or(std::vector<float>{});
        input_.curveVertexCounts = s.getIntArray("curveVertexCounts").value_or(std::vector<int32_t>{});
        input_.basis = basisOf(s);
        input_.wrap = wrapOf(s);
        input_.widths = pullWidths(s);
        shutterPoints_ = pullShutterPoints(s, input_.points, ctx);
    }
    if (topology || s.dirty("normals")) input_.normals = pullPrimvar(s, "normals", 3);
    if (topology || s.anyDirty({"primvars:displayColor", "primvars:widths"})) {
        input_.displayColor = pullPrimvar(s, "primvars:displayColor", 3);
        if (!s.getFloatArray("widths")) input_.widths = pullWidths(s);
    }
    input_.displayOpacity = varyingOpacity_;  // a constant one is the gprim's (pullGprim)
    if (std::string problem = curvesProblem(input_); !problem.empty()) throw PrimDataError(s.path() + ": " + problem);
    if (input_.points.empty()) return dropGeometry(ctx);  // nothing to draw, nothing kept from before
    if (sidesLevel_ < 0) return;                        // tessellated once the view is known (chooseViewDependentDetail)
    // The cap coarsens sides and steps together, one level at a time.
    const int finest = std::max(sidesLevel_, stepsLevel_);
    auto detailAt = [&](int level) {
        return CurveDetail{implicitSegments(sidesLevel_ - (finest - level)), 1 << std::max(0, stepsLevel_ - (finest - level))};
    };
    CappedLevel capped = capTessellation(finest, 0, [&](int level) { return curveTriangleCount(input_, detailAt(level)); },
                                         s.path());
    detail_ = detailAt(capped.level);
    MeshGeometry geometry = tessellateCurves(input_, detail_);
    if (!capped.warning.empty()) geometry.warnings.push_back(capped.warning);
    const size_t vertexCount = setGeometry(std::move(geometry), ctx, s.path());
    setShutterPositions(shutterEnds(shutterPoints_, input_, [&](const CurvesInput& in) { return tessellateCurves(in, detail_); }),
                        vertexCount, ctx, s.path());
}

void Points::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext& ctx) {
    pullGprim(s, ctx);
    if (!geometryDirty(s, bits)) return;
    if (s.anyDirtyBut({"transform", "visibility", "purpose", "doubleSided", "material:binding"})) {
        input_.points = s.getFloatArray("points").value_or(std::vector<float>{});
        input_.widths = pullWidths(s);
        input_.displayColor = pullPrimvar(s, "primvars:displayColor", 3);
        shutterPoints_ = pullShutterPoints(s, input_.points, ctx);
    }
    input_.displayOpacity = varyingOpacity_;  // a constant one is the gprim's (pullGprim)
    if (std::string problem = pointsProblem(input_); !problem.empty()) throw PrimDataError(s.path() + ": " + problem);
    if (input_.points.empty()) return dropGeometry(ctx);  // nothing to draw, nothing kept from before
    if (const uint64_t triangles = pointTriangleCount(input_); triangles > kMaxTessellatedTriangles)
        throw PrimDataError(s.path() + ": " + std::to_string(input_.points.size() / 3) + " points need " +
                            std::to_string(triangles) + " triangles, over the cap of " +
                            std::to_string(kMaxTessellatedTriangles) + " per prim");
    MeshGeometry geometry = pointImpostorBoxes(input_);
    const size_t vertexCount = setGeometry(std::move(geometry), ctx, s.path());
    setShutterPositions(shutterEnds(shutterPoints_, input_, pointImpostorBoxes), vertexCount, ctx, s.path());
}

}  // namespace obscura::delegate
