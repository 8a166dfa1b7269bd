// Transforms and visibility computed as UsdGeomXformable / UsdGeomImageable do.
#include <algorithm>
#include <set>
#include <string_view>

#include "harness/usda/matrix4.h"
#include "harness/usda/stage.h"

namespace obscura::usda {

namespace {

using matrix4::Matrix4;

constexpr std::string_view kResetXformStack = "!resetXformStack!";
constexpr std::string_view kInvertPrefix = "!invert!";
constexpr std::string_view kOpPrefix = "xformOp:";

std::vector<std::string> opOrder(const Prim& prim, double time) {
    const Attribute* order = prim.attribute("xformOpOrder");
    if (!order) return {};
    const std::optional<Value> value = order->evaluate(time);
    return value ? value->strings.vector() : std::vector<std::string>{};
}

// "xformOp:rotateXYZ:pivot" -> "rotateXYZ".
std::string_view opType(std::string_view attrName) {
    if (!attrName.starts_with(kOpPrefix)) return {};
    attrName.remove_prefix(kOpPrefix.size());
    return attrName.substr(0, attrName.find(':'));
}

int axisIndex(char axis) { return axis - 'X'; }

// The matrix of one op from its value; unknown op types contribute nothing.
Matrix4 opMatrix(std::string_view type, const Value& value) {
    const std::vector<double>& v = value.numbers;
    if (type == "translate" && v.size() >= 3) return matrix4::translation(v[0], v[1], v[2]);
    if (type == "scale" && v.size() >= 3) return matrix4::scale(v[0], v[1], v[2]);
    if (type == "orient" && v.size() >= 4) return matrix4::rotation(v[0], v[1], v[2], v[3]);
    if (type == "transform" && v.size() >= 16) {
        Matrix4 m;
        std::copy(v.begin(), v.begin() + 16, m.begin());
        return m;
    }
    if (type.size() == 7 && type.starts_with("rotate") && !v.empty()) {
        const char axis = type[6];
        if (axis >= 'X' && axis <= 'Z') return matrix4::rotation(axisIndex(axis), v[0]);
    }
    if (type.size() == 9 && type.starts_with("rotate") && v.size() >= 3) {
        // rotateXYZ rotates about X first: with row vectors that is Rx * Ry * Rz. The value holds
        // the X, Y and Z angles whatever the order.
        Matrix4 m = matrix4::identity();
        for (const char axis : type.substr(6)) {
            if (axis < 'X' || axis > 'Z') return matrix4::identity();
            m = matrix4::multiply(m, matrix4::rotation(axisIndex(axis), v[static_cast<size_t>(axisIndex(axis))]));
        }
        return m;
    }
    return matrix4::identity();
}

}  // namespace

std::array<double, 16> Stage::localTransform(const Prim& prim, double time, bool* resetsXformStack) const {
    Matrix4 local = matrix4::identity();
    bool reset = false;
    for (std::string_view entry : opOrder(prim, time)) {
        if (entry == kResetXformStack) {
            // Ops before a reset are discarded along with the parent transforms.
            reset = true;
            local = matrix4::identity();
            continue;
        }
        const bool invert = entry.starts_with(kInvertPrefix);
        if (invert) entry.remove_prefix(kInvertPrefix.size());
        const Attribute* attr = prim.attribute(std::string(entry));
        const std::optional<Value> value = attr ? attr->evaluate(time) : std::nullopt;
        if (!value) continue;
        Matrix4 op = opMatrix(opType(entry), *value);
        if (invert) op = matrix4::inverse(op);
        // The first op in the order is the outermost: local = op_n * ... * op_1 for row vectors.
        local = matrix4::multiply(op, local);
    }
    if (resetsXformStack) *resetsXformStack = reset;
    return local;
}

std::array<double, 16> Stage::worldTransform(const Prim& prim, double time) const {
    bool reset = false;
    Matrix4 world = localTransform(prim, time, &reset);
    for (const Prim* ancestor = prim.parent; ancestor && !reset; ancestor = ancestor->parent)
        world = matrix4::multiply(world, localTransform(*ancestor, time, &reset));
    return world;
}

std::vector<double> Stage::transformSampleTimes(const Prim& prim, double from, double to) const {
    std::set<double> times;
    for (const Prim* p = &prim; p; p = p->parent) {
        // xformOpOrder is uniform, so its default names the ops.
        bool reset = false;
        for (std::string_view entry : opOrder(*p, 0.0)) {
            if (entry == kResetXformStack) {
                reset = true;
                continue;
            }
            if (entry.starts_with(kInvertPrefix)) entry.remove_prefix(kInvertPrefix.size());
            if (const Attribute* attr = p->attribute(std::string(entry))) {
                for (const auto& sample : attr->timeSamples)
                    if (sample.first >= from && sample.first <= to) times.insert(sample.first);
                if (attr->spline && attr->timeSamples.empty())
                    for (double t : attr->spline->sampleTimes(from, to)) times.insert(t);
            }
        }
        if (reset) break;
    }
    return {times.begin(), times.end()};
}

bool Stage::isVisible(const Prim& prim, double time) const {
    for (const Prim* p = &prim; p; p = p->parent) {
        const Attribute* visibility = p->attribute("visibility");
        if (!visibility) continue;
        const std::optional<Value> value = visibility->evaluate(time);
        if (value && !value->strings.empty() && value->strings.front() == "invisible") return false;
    }
    return true;
}

bool Stage::hasAnimatedVisibility(const Prim& prim) const {
    for (const Prim* p = &prim; p; p = p->parent)
        if (const Attribute* visibility = p->attribute("visibility"); visibility && visibility->isAnimated())
            return true;
    return false;
}

namespace {
// Prim types that are not UsdGeomImageable: a purpose authored on them is not theirs to pass on
// (typeless prims, shading and render-settings prims, GeomSubset).
bool isImageable(const Prim& prim) {
    static const std::set<std::string> kNotImageable = {"",          "Material",       "Shader",        "NodeGraph",
                                                        "GeomSubset", "RenderSettings", "RenderProduct", "RenderVar"};
    return !kNotImageable.count(prim.typeName);
}
}  // namespace

const Attribute* Stage::purposeOpinion(const Prim& prim) const {
    for (const Prim* p = &prim; p; p = p->parent) {
        if (!isImageable(*p)) continue;
        const Attribute* purpose = p->attribute("purpose");
        if (purpose && purpose->defaultValue && !purpose->defaultValue->empty()) return purpose;
    }
    return nullptr;
}

}  // namespace obscura::usda
