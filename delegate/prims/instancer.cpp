#include "delegate/prims/instancer.h"

#include "delegate/prims/mesh.h"
#include "delegate/prims/point_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

namespace obscura::delegate {

Matrix4d instanceTransform(const float* p, const float* q, const float* s) {
    double w = q ? q[0] : 1.0, x = q ? q[1] : 0.0, y = q ? q[2] : 0.0, z = q ? q[3] : 0.0;
    double n = std::sqrt(w * w + x * x + y * y + z * z);
    if (n > 0) w /= n, x /= n, y /= n, z /= n;
    // Rows are the images of the local axes (row-vector convention).
    double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
                      {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
                      {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}};
    Matrix4d m = kIdentity;
    for (int row = 0; row < 3; ++row)
        for (int c = 0; c < 3; ++c) m[row * 4 + c] = r[row][c] * (s ? s[row] : 1.0);
    for (int c = 0; c < 3; ++c) m[12 + c] = p[c];
    return m;
}

std::vector<float> turnOrientations(const std::vector<float>& orientations, const std::vector<float>& angularVelocities,
                                    double seconds) {
    std::vector<float> turned(orientations.size());
    for (size_t i = 0; i < orientations.size() / 4; ++i) {
        const float* w = &angularVelocities[3 * i];
        double speed = std::sqrt(double(w[0]) * w[0] + double(w[1]) * w[1] + double(w[2]) * w[2]);  // degrees/s
        double half = 0.5 * speed * seconds * std::numbers::pi / 180.0;
        double s = speed > 0.0 ? std::sin(half) / speed : 0.0;
        // The turn (w, x, y, z), then the orientation before it: turn * orientation (Hamilton).
        double a[4] = {std::cos(half), w[0] * s, w[1] * s, w[2] * s};
        const float* q = &orientations[4 * i];
        turned[4 * i] = float(a[0] * q[0] - a[1] * q[1] - a[2] * q[2] - a[3] * q[3]);
        turned[4 * i + 1] = float(a[0] * q[1] + a[1] * q[0] + a[2] * q[3] - a[3] * q[2]);
        turned[4 * i + 2] = float(a[0] * q[2] - a[1] * q[3] + a[2] * q[0] + a[3] * q[1]);
        turned[4 * i + 3] = float(a[0] * q[3] + a[1] * q[2] - a[2] * q[1] + a[3] * q[0]);
    }
    return turned;
}

namespace {

// Instance primvar `name`: one element per instance or one for all; otherwise ignored with a
// warning.
std::optional<MeshPrimvar> instancePrimvar(SceneAccess& s, const char* name, size_t components, size_t instances,
                                           std::vector<std::string>& warnings) {
    std::optional<MeshPrimvar> primvar = pullPrimvar(s, name, components);
    if (!primvar) return std::nullopt;
    const size_t count = primvar->values.size() / components;
    if (count == 1 || count == instances) return primvar;
    warnings.push_back(s.path() + ": " + name + " has " + std::to_string(count) + " elements but there are " +
                       std::to_string(instances) + " instances; ignored");
    return std::nullopt;
}

// Element `i` of a validated instance primvar (its only one when constant).
const float* elementOf(const MeshPrimvar& primvar, size_t i) {
    return &primvar.values[(primvar.values.size() == primvar.components ? 0 : i) * primvar.components];
}

}  // namespace

Instancer::InstanceDisplay Instancer::displayOf(size_t index, size_t k) const {
    const size_t i = size_t(instanceIndexOf(index, k));
    InstanceDisplay display;
    if (displayColor_) {
        const float* c = elementOf(*displayColor_, i);
        display.color = std::array<float, 3>{c[0], c[1], c[2]};
    }
    if (displayOpacity_) display.opacity = *elementOf(*displayOpacity_, i);
    return display;
}

bool Instancer::hasTranslucentInstances() const {
    return displayOpacity_ &&
           std::any_of(displayOpacity_->values.begin(), displayOpacity_->values.end(), [](float o) { return o < 1.0f; });
}

int Instancer::prototypeOf(const std::string& meshPath) const {
    for (size_t i = 0; i < prototypes_.size(); ++i) {
        const std::string& root = prototypes_[i];
        if (meshPath == root || (meshPath.size() > root.size() && meshPath.compare(0, root.size(), root) == 0 &&
                                 meshPath[root.size()] == '/'))
            return static_cast<int>(i);
    }
    return -1;
}

void Instancer::reset() {
    prototypes_.clear();
    protoIndices_.clear();
    byPrototype_.clear();
    indicesByPrototype_.clear();
    shutterPoints_.reset();
    shutterPlacements_.reset();
    displayColor_.reset();
    displayOpacity_.reset();
    warnings_.clear();
}

void Instancer::pull(SceneAccess& s, ObscuraDirtyBits, SyncContext& ctx) {
    const bool shutterOpen = ctx.shutterClose > ctx.shutterOpen;
    if (s.dirty("transform")) {
        transform_ = s.sampleTransform(s.time(), s.time()).front().matrix;
        shutterTransforms_ = s.sampleTransform(ctx.shutterOpen, ctx.shutterClose);
    }
    if (s.dirty("visibility")) visible_ = s.getToken("visibility") != "invisible";
    if (s.dirty("invisibleIds")) invisible_ = s.getIntArray("invisibleIds").value_or(std::vector<int32_t>{});
    if (s.dirty("prototypes")) prototypes_ = s.getPathArray("prototypes");
    if (s.dirty("protoIndices")) protoIndices_ = s.getIntArray("protoIndices").value_or(std::vector<int32_t>{});
    if (s.anyDirty({"protoIndices", "primvars:displayColor", "primvars:displayOpacity"})) {
        warnings_.clear();
        displayColor_ = instancePrimvar(s, "primvars:displayColor", 3, protoIndices_.size(), warnings_);
        displayOpacity_ = instancePrimvar(s, "primvars:displayOpacity", 1, protoIndices_.size(), warnings_);
    }
    if (s.anyDirty({"positions", "orientations", "scales", "velocities", "accelerations", "angularVelocities"})) {
        points_ = PointArrays{s.getFloatArray("positions").value_or(std::vector<float>{}),
                              s.getFloatArray("orientations").value_or(std::vector<float>{}),
                              s.getFloatArray("scales").value_or(std::vector<float>{})};
        shutterPoints_.reset();
        if (shutterOpen) {
            // USD moves instances by their velocities and turns them by their angular velocities
            // where either is authored, and interpolates the time samples only otherwise
            // (UsdGeomPointInstancer::ComputeInstanceTransformsAtTime; point_motion.h).
            const size_t n = points_.positions.size() / 3;
            auto motion = pointMotion(s.getFloatArray("velocities"), s.getFloatArray("accelerations"), n);
            auto angular = s.getFloatArray("angularVelocities");
            if (!angular || angular->size() != 3 * n || points_.orientations.size() != 4 * n) angular.reset();
            auto pointsAt = [&](double time) {
                double seconds = secondsBetween(s.time(), time, ctx.timeCodesPerSecond);
                if (motion || angular)
                    return PointArrays{motion ? movePoints(points_.positions, *motion, seconds) : points_.positions,
                                       angular ? turnOrientations(points_.orientations, *angular, seconds)
                                               : points_.orientations,
                                       points_.scales};
                return PointArrays{sampledOrFrame(s.getFloatArrayAt("positions", time), points_.positions),
                                   sampledOrFrame(s.getFloatArrayAt("orientations", time), points_.orientations),
                                   sampledOrFrame(s.getFloatArrayAt("scales", time), points_.scales)};
            };
            std::array<PointArrays, 2> ends{pointsAt(ctx.shutterOpen), pointsAt(ctx.shutterClose)};
            auto same = [this](const PointArrays& a) {
                return a.positions == points_.positions && a.orientations == points_.orientations &&
                       a.scales == points_.scales;
            };
            if (!same(ends[0]) || !same(ends[1])) shutterPoints_ = std::move(ends);
        }
    }
    shutter_ = {ctx.shutterOpen, ctx.shutterClose};
    indicesByPrototype_ = visibleByPrototype(s.path());
    byPrototype_ = placementsOf(points_, transform_, s.path());
    // Placements at the shutter's ends, for motion blur and the reference's sub-frames.
    shutterPlacements_.reset();
    if (shutterPoints_ || shutterTransforms_.size() > 1) {
        std::array<Placements, 2> ends;
        for (int end = 0; end < 2; ++end)
            ends[size_t(end)] = placementsOf(shutterPoints_ ? (*shutterPoints_)[size_t(end)] : points_,
                                             interpolateTransform(shutterTransforms_, shutter_[size_t(end)]), s.path());
        for (size_t p = 0; p < byPrototype_.size(); ++p)
            if (ends[0][p].size() != byPrototype_[p].size() || ends[1][p].size() != byPrototype_[p].size())
                throw PrimDataError(s.path() + ": the instances change within the shutter");
        shutterPlacements_ = std::move(ends);
    }
}

Matrix4d Instancer::instanceAt(size_t index, size_t k, double time) const {
    if (!shutterPlacements_) return byPrototype_.at(index).at(k);
    double f = shutter_[1] > shutter_[0] ? std::clamp((time - shutter_[0]) / (shutter_[1] - shutter_[0]), 0.0, 1.0) : 0.5;
    const Matrix4d& a = (*shutterPlacements_)[0].at(index).at(k);
    const Matrix4d& b = (*shutterPlacements_)[1].at(index).at(k);
    Matrix4d m;
    for (size_t i = 0; i < m.size(); ++i) m[i] = std::lerp(a[i], b[i], f);
    return m;
}

Instancer::Placements Instancer::placementsOf(const PointArrays& points, const Matrix4d& transform,
                                              const std::string& path) const {
    const size_t n = protoIndices_.size();
    if (points.positions.size() != 3 * n)
        throw PrimDataError(path + ": positions has " + std::to_string(points.positions.size() / 3) + " entries for " +
                            std::to_string(n) + " instances");
    if (!points.orientations.empty() && points.orientations.size() != 4 * n)
        throw PrimDataError(path + ": orientations has " + std::to_string(points.orientations.size() / 4) +
                            " entries for " + std::to_string(n) + " instances");
    if (!points.scales.empty() && points.scales.size() != 3 * n)
        throw PrimDataError(path + ": scales has " + std::to_string(points.scales.size() / 3) + " entries for " +
                            std::to_string(n) + " instances");
    Placements placements(prototypes_.size());
    for (size_t proto = 0; proto < indicesByPrototype_.size(); ++proto)
        for (int32_t index : indicesByPrototype_[proto]) {
            size_t i = size_t(index);
            Matrix4d local = instanceTransform(&points.positions[3 * i],
                                               points.orientations.empty() ? nullptr : &points.orientations[4 * i],
                                               points.scales.empty() ? nullptr : &points.scales[3 * i]);
            placements[proto].push_back(multiply(local, transform));
        }
    return placements;
}

std::vector<std::vector<int32_t>> Instancer::visibleByPrototype(const std::string& path) const {
    std::set<int32_t> hidden(invisible_.begin(), invisible_.end());
    std::vector<std::vector<int32_t>> visible(prototypes_.size());
    for (size_t i = 0; i < protoIndices_.size(); ++i) {
        int32_t proto = protoIndices_[i];
        if (proto < 0 || size_t(proto) >= prototypes_.size())
            throw PrimDataError(path + ": protoIndices[" + std::to_string(i) + "] = " + std::to_string(proto) +
                                " is outside the " + std::to_string(prototypes_.size()) + " prototypes");
        if (!hidden.count(int32_t(i))) visible[size_t(proto)].push_back(int32_t(i));
    }
    return visible;
}

}  // namespace obscura::delegate
