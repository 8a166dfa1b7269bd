#include "delegate/prims/nurbs_patch.h"

#include "delegate/implicit_tessellation.h"

#include <algorithm>

namespace obscura::delegate {
namespace {

// What a sync re-reads beside the placement, visibility and binding: the surface and its primvars.
constexpr std::initializer_list<const char*> kPlacement = {"transform", "visibility", "purpose", "doubleSided",
                                                           "material:binding"};

NurbsDirection pullDirection(SceneAccess& s, const char* vertexCount, const char* order, const char* knots,
                             const char* range) {
    NurbsDirection d;
    d.vertexCount = s.getInt(vertexCount);
    d.order = s.getInt(order);
    const std::vector<float> k = s.getFloatArray(knots).value_or(std::vector<float>{});
    d.knots.assign(k.begin(), k.end());
    const std::array<float, 2> r = s.getFloat2(range);
    d.range = {r[0], r[1]};
    return d;
}

// Steps per span at a level: 2^level.
int stepsAt(int level) { return 1 << std::max(0, level); }

// The level whose steps are at least `steps`.
int levelFor(int steps) {
    int level = 0;
    while (stepsAt(level) < steps) ++level;
    return level;
}

// Groups of `n` floats as arrays of doubles.
template <size_t N>
std::vector<std::array<double, N>> tuples(const std::vector<float>& flat) {
    std::vector<std::array<double, N>> out(flat.size() / N);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t k = 0; k < N; ++k) out[i][k] = flat[i * N + k];
    return out;
}

NurbsTrimCurves pullTrimCurves(SceneAccess& s) {
    NurbsTrimCurves c;
    c.counts = s.getIntArray("trimCurve:counts").value_or(std::vector<int32_t>{});
    if (c.counts.empty()) return c;
    c.orders = s.getIntArray("trimCurve:orders").value_or(std::vector<int32_t>{});
    c.vertexCounts = s.getIntArray("trimCurve:vertexCounts").value_or(std::vector<int32_t>{});
    const std::vector<float> knots = s.getFloatArray("trimCurve:knots").value_or(std::vector<float>{});
    c.knots.assign(knots.begin(), knots.end());
    c.ranges = tuples<2>(s.getFloatArray("trimCurve:ranges").value_or(std::vector<float>{}));
    c.points = tuples<3>(s.getFloatArray("trimCurve:points").value_or(std::vector<float>{}));
    return c;
}

}  // namespace

std::vector<DetailSphere> NurbsPatch::detailSpheres() const {
    std::vector<DetailSphere> spheres;
    const int orderU = input_.u.order, orderV = input_.v.order;
    for (int sv = 0; sv < input_.v.spanCount(); ++sv)
        for (int su = 0; su < input_.u.spanCount(); ++su) {
            Aabb box;
            for (int j = sv; j < sv + orderV; ++j)
                for (int i = su; i < su + orderU; ++i) {
                    const float* p = &input_.points[(size_t(j) * size_t(input_.u.vertexCount) + size_t(i)) * 3];
                    box.extend({p[0], p[1], p[2]});
                }
            const std::array<double, 3> c = box.centre();
            spheres.push_back({c, length({box.max[0] - c[0], box.max[1] - c[1], box.max[2] - c[2]})});
        }
    return spheres;
}

bool NurbsPatch::chooseDetail(double pixelsPerUnit) {
    std::array<int, 2> levels = levels_;
    for (size_t k = 0; k < 2; ++k)
        levels[k] = std::max(chooseImplicitLevel(wantedStepLevel(bend_[k] * pixelsPerUnit, kMaxChordErrorPixels), levels_[k]),
                             levelFor(trimSteps_[k]));
    if (levels == levels_) return false;
    levels_ = levels;
    markDirty(kDirtyTessellation);
    return true;
}

void NurbsPatch::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext& ctx) {
    pullGprim(s, ctx);
    const bool surface = s.anyDirtyBut(kPlacement);
    if (!surface && !(bits & kDirtyTessellation)) return;
    if (surface) {
        NurbsPatchInput in;
        in.points = s.getFloatArray("points").value_or(std::vector<float>{});
        in.u = pullDirection(s, "uVertexCount", "uOrder", "uKnots", "uRange");
        in.v = pullDirection(s, "vVertexCount", "vOrder", "vKnots", "vRange");
        in.pointWeights = s.getFloatArray("pointWeights").value_or(std::vector<float>{});
        in.leftHanded = s.getToken("orientation") == "leftHanded";
        in.displayColor = pullPrimvar(s, "primvars:displayColor", 3);
        in.displayOpacity = varyingOpacity_;  // a constant one is the gprim's (pullGprim)
        in.st = pullPrimvar(s, "primvars:st", 2);
        in.trimCurves = pullTrimCurves(s);
        // Only a valid patch is kept: a later change of view tessellates what is kept.
        input_ = {};
        if (in.points.empty()) return dropGeometry(ctx);  // nothing to draw, nothing kept from before
        if (std::string problem = nurbsPatchProblem(in); !problem.empty()) throw PrimDataError(s.path() + ": " + problem);
        input_ = std::move(in);
        // The trim boundary bends like the surface: its chords keep the same bound.
        const std::array<double, 2> shape = nurbsBendMagnitude(input_), trim = nurbsTrimBend(input_);
        bend_ = {std::max(shape[0], trim[0]), std::max(shape[1], trim[1])};
        trimSteps_ = nurbsTrimSteps(input_);
        shutterPoints_ = pullShutterPoints(s, input_.points, ctx);
    }
    if (input_.points.empty() || levels_[0] < 0) return;  // tessellated once the view is known (chooseViewDependentDetail)
    // The cap coarsens both directions together, one level at a time.
    const int finest = std::max(levels_[0], levels_[1]);
    auto stepsAtLevel = [&](int level) {
        return std::array<int, 2>{stepsAt(levels_[0] - (finest - level)), stepsAt(levels_[1] - (finest - level))};
    };
    const CappedLevel capped = capTessellation(
        finest, 0, [&](int level) { return nurbsTriangleCount(input_, stepsAtLevel(level)); }, s.path());
    steps_ = stepsAtLevel(capped.level);
    auto build = [&](const NurbsPatchInput& in) {
        NurbsTessellation tessellation = tessellateNurbsPatch(in, steps_);
        auto built = buildMeshGeometry(tessellation.mesh);
        if (auto* problem = std::get_if<std::string>(&built)) throw PrimDataError(s.path() + ": " + *problem);
        MeshGeometry& geometry = std::get<MeshGeometry>(built);
        geometry.warnings.insert(geometry.warnings.end(), tessellation.warnings.begin(), tessellation.warnings.end());
        return std::move(geometry);
    };
    MeshGeometry geometry = build(input_);
    if (!capped.warning.empty()) geometry.warnings.push_back(capped.warning);
    const size_t vertexCount = setGeometry(std::move(geometry), ctx, s.path());
    setShutterPositions(shutterEnds(shutterPoints_, input_, build), vertexCount, ctx, s.path());
}

}  // namespace obscura::delegate
