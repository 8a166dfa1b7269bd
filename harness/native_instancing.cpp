#include "harness/native_instancing.h"

#include <cmath>
#include <map>

namespace obscura::harness {

namespace {

// Where the host's instancer prims live: beside the stage's namespace, as the framing camera is.
const std::string kInstancersPath = "/ObscuraInstancers/Prototype";

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

bool underAny(const usda::Prim& prim, const std::unordered_set<const usda::Prim*>& roots) {
    for (const usda::Prim* p = &prim; p; p = p->parent)
        if (roots.count(p)) return true;
    return false;
}

usda::Value arrayValue(const char* typeName, int tupleSize, std::vector<double> numbers) {
    usda::Value value;
    value.typeName = typeName;
    value.isArray = true;
    value.tupleSize = tupleSize;
    value.numbers = std::move(numbers);
    return value;
}

}  // namespace

std::optional<InstancePlacement> decomposeInstanceTransform(const std::array<double, 16>& m) {
    // Row i is local axis i's image: its length is the scale along it, its direction the
    // rotation's row (row-vector convention, as instanceTransform builds it in the plugin).
    InstancePlacement placement{{m[12], m[13], m[14]}, {1, 0, 0, 0}, {}};
    std::array<Vec3, 3> r;
    for (size_t row = 0; row < 3; ++row) {
        const Vec3 axis{m[4 * row], m[4 * row + 1], m[4 * row + 2]};
        placement.scale[row] = std::sqrt(dot(axis, axis));
        if (!(placement.scale[row] > 0.0)) return std::nullopt;
        for (size_t c = 0; c < 3; ++c) r[row][c] = axis[c] / placement.scale[row];
    }
    constexpr double kPerpendicular = 1e-6;
    if (std::abs(dot(r[0], r[1])) > kPerpendicular || std::abs(dot(r[0], r[2])) > kPerpendicular ||
        std::abs(dot(r[1], r[2])) > kPerpendicular)
        return std::nullopt;
    // A mirror is a negative scale along the first axis.
    if (dot(r[0], cross(r[1], r[2])) < 0.0) {
        placement.scale[0] = -placement.scale[0];
        for (double& c : r[0]) c = -c;
    }
    // The quaternion of the rotation whose rows are r (the transpose of the column-vector matrix),
    // from its largest diagonal term for precision (Shepperd 78).
    auto& [w, x, y, z] = placement.orientation;
    const double trace = r[0][0] + r[1][1] + r[2][2];
    if (trace > 0.0) {
        const double s = 2.0 * std::sqrt(trace + 1.0);
        w = 0.25 * s, x = (r[1][2] - r[2][1]) / s, y = (r[2][0] - r[0][2]) / s, z = (r[0][1] - r[1][0]) / s;
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]);
        w = (r[1][2] - r[2][1]) / s, x = 0.25 * s, y = (r[1][0] + r[0][1]) / s, z = (r[2][0] + r[0][2]) / s;
    } else if (r[1][1] > r[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]);
        w = (r[2][0] - r[0][2]) / s, x = (r[0][1] + r[1][0]) / s, y = 0.25 * s, z = (r[2][1] + r[1][2]) / s;
    } else {
        const double s = 2.0 * std::sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]);
        w = (r[0][1] - r[1][0]) / s, x = (r[2][0] + r[0][2]) / s, y = (r[2][1] + r[1][2]) / s, z = 0.25 * s;
    }
    return placement;
}

NativeInstancing::NativeInstancing(const usda::Stage& stage, const HandedDown& handedDown, double time) {
    std::unordered_set<const usda::Prim*> outermost;  // instances not inside another
    std::map<std::string, size_t> byKey;
    for (const usda::Prim* prim : stage.prims()) {
        if (prim->instancingKey.empty() || (prim->parent && underAny(*prim->parent, outermost))) continue;
        outermost.insert(prim);
        if (!decomposeInstanceTransform(stage.worldTransform(*prim, time))) continue;
        const std::string key = prim->instancingKey + '\n' + handedDown(*prim);
        auto [group, added] = byKey.emplace(key, instancers_.size());
        if (added) {
            instancers_.push_back({kInstancersPath + std::to_string(instancers_.size() + 1), prim, {}});
            byPath_[instancers_.back().path] = group->second;
            prototypes_[prim] = group->second;
        } else {
            others_.insert(prim);
        }
        instancers_[group->second].instances.push_back(prim);
    }
}

bool samePlacements(const NativeInstancer& a, const usda::Stage& stageOfA, const NativeInstancer& b,
                    const usda::Stage& stageOfB, double time) {
    if (a.prototype->path != b.prototype->path || a.instances.size() != b.instances.size()) return false;
    for (size_t i = 0; i < a.instances.size(); ++i) {
        const usda::Prim& x = *a.instances[i];
        const usda::Prim& y = *b.instances[i];
        if (x.path != y.path || stageOfA.worldTransform(x, time) != stageOfB.worldTransform(y, time) ||
            stageOfA.transformSampleTimes(x) != stageOfB.transformSampleTimes(y) ||
            stageOfA.isVisible(x, time) != stageOfB.isVisible(y, time) ||
            stageOfA.hasAnimatedVisibility(x) != stageOfB.hasAnimatedVisibility(y))
            return false;
    }
    return true;
}

const NativeInstancer* NativeInstancing::instancer(const std::string& path) const {
    const auto it = byPath_.find(path);
    return it == byPath_.end() ? nullptr : &instancers_[it->second];
}

bool NativeInstancing::drawnByInstancer(const usda::Prim& prim) const { return !others_.empty() && underAny(prim, others_); }

const NativeInstancer* NativeInstancing::prototypeHolding(const usda::Prim& prim) const {
    if (prototypes_.empty()) return nullptr;
    for (const usda::Prim* p = &prim; p; p = p->parent)
        if (const auto it = prototypes_.find(p); it != prototypes_.end()) return &instancers_[it->second];
    return nullptr;
}

bool NativeInstancing::hasAnimatedTransforms(const NativeInstancer& instancer, const usda::Stage& stage) const {
    for (const usda::Prim* instance : instancer.instances)
        if (!stage.transformSampleTimes(*instance).empty()) return true;
    return false;
}

bool NativeInstancing::hasAnimatedVisibility(const NativeInstancer& instancer, const usda::Stage& stage) const {
    for (const usda::Prim* instance : instancer.instances)
        if (stage.hasAnimatedVisibility(*instance)) return true;
    return false;
}

std::optional<usda::Value> NativeInstancing::value(const NativeInstancer& instancer, const usda::Stage& stage,
                                                   const std::string& attribute, double time) const {
    const size_t count = instancer.instances.size();
    if (attribute == "protoIndices") return arrayValue("int", 1, std::vector<double>(count, 0.0));
    if (attribute == "invisibleIds") {
        std::vector<double> hidden;
        for (size_t i = 0; i < count; ++i)
            if (!stage.isVisible(*instancer.instances[i], time)) hidden.push_back(double(i));
        return arrayValue("int", 1, std::move(hidden));
    }
    const bool positions = attribute == "positions", orientations = attribute == "orientations";
    if (!positions && !orientations && attribute != "scales") return std::nullopt;
    std::vector<double> numbers;
    numbers.reserve(count * (orientations ? 4 : 3));
    for (const usda::Prim* instance : instancer.instances) {
        const std::array<double, 16> m = stage.worldTransform(*instance, time);
        // XXX: an instance that shears only later in an animation keeps its translation alone
        // there; instances that shear at the start time are not instanced (the constructor).
        const InstancePlacement placement =
            decomposeInstanceTransform(m).value_or(InstancePlacement{{m[12], m[13], m[14]}, {1, 0, 0, 0}, {1, 1, 1}});
        if (positions) numbers.insert(numbers.end(), placement.position.begin(), placement.position.end());
        else if (orientations) numbers.insert(numbers.end(), placement.orientation.begin(), placement.orientation.end());
        else numbers.insert(numbers.end(), placement.scale.begin(), placement.scale.end());
    }
    return orientations ? arrayValue("quatd", 4, std::move(numbers)) : arrayValue("float3", 3, std::move(numbers));
}

}  // namespace obscura::harness
