#include "delegate/scene_access.h"

#include <cmath>
#include <cstring>
#include <span>

namespace obscura::delegate {

SceneAccess::SceneAccess(const ObscuraSceneDelegate& sd, const schema::PrimSchema& schema, const std::string& path,
                         double time, ObscuraDirtyBits dirty)
    : sd_(sd), schema_(schema), path_(path), time_(time), dirty_(dirty) {}

bool SceneAccess::dirty(const char* name) const { return (attribute(name).dirtyBit & dirty_) != 0; }

bool SceneAccess::anyDirty(std::initializer_list<const char*> names) const {
    for (const char* name : names)
        if (dirty(name)) return true;
    return false;
}

bool SceneAccess::anyDirtyBut(std::initializer_list<const char*> except) const {
    for (const char* name : except) attribute(name);  // names the schema lacks are a programming error
    for (const schema::AttributeSchema& a : std::span(schema_.attributes, schema_.attributeCount)) {
        bool excepted = false;
        for (const char* name : except) excepted = excepted || std::strcmp(name, a.name) == 0;
        if (!excepted && (a.dirtyBit & dirty_)) return true;
    }
    return false;
}

void SceneAccess::fail(const std::string& message) const { throw PrimDataError(path_ + ": " + message); }

const schema::AttributeSchema& SceneAccess::attribute(const char* name) const {
    // The delegate only asks for attributes its schemas declare: a miss is a programming error.
    return schema::attributeOf(schema_, name);
}

std::optional<ObscuraValue> SceneAccess::fetch(const schema::AttributeSchema& a) { return fetchAt(a, time_); }

std::optional<ObscuraValue> SceneAccess::fetchAt(const schema::AttributeSchema& a, double time) {
    if (!sd_.getValue) return std::nullopt;
    ObscuraValue v{};
    ObscuraStatus s = sd_.getValue(sd_.userData, path_.c_str(), a.name, time, &v);
    if (s == OBSCURA_ERROR_NOT_FOUND) return std::nullopt;
    if (s != OBSCURA_OK) fail(std::string("the host failed to provide ") + a.name + " (status " + std::to_string(s) + ")");
    std::string problem = schema::checkValue(a, v);
    if (!problem.empty()) fail(problem);
    return v;
}

namespace {
double numberAt(const ObscuraValue& v, size_t i) {
    switch (v.type) {
        case OBSCURA_VALUE_BOOL:
        case OBSCURA_VALUE_INT:
        case OBSCURA_VALUE_INT2: return static_cast<const int32_t*>(v.data)[i];
        case OBSCURA_VALUE_DOUBLE:
        case OBSCURA_VALUE_MATRIX4D: return static_cast<const double*>(v.data)[i];
        default: return static_cast<const float*>(v.data)[i];
    }
}
}  // namespace

bool SceneAccess::getBool(const char* name) {
    const auto& a = attribute(name);
    auto v = fetch(a);
    return v ? numberAt(*v, 0) != 0 : (a.defaultCount ? a.defaultNumbers[0] != 0 : false);
}

int32_t SceneAccess::getInt(const char* name) {
    const auto& a = attribute(name);
    auto v = fetch(a);
    return v ? static_cast<int32_t>(numberAt(*v, 0)) : static_cast<int32_t>(a.defaultCount ? a.defaultNumbers[0] : 0);
}

double SceneAccess::getDouble(const char* name) {
    const auto& a = attribute(name);
    auto v = fetch(a);
    return v ? numberAt(*v, 0) : (a.defaultCount ? a.defaultNumbers[0] : 0.0);
}

template <typename T, size_t N>
std::array<T, N> SceneAccess::getTuple(const char* name) {
    const auto& a = attribute(name);
    auto v = fetch(a);
    std::array<T, N> r{};
    for (size_t i = 0; i < N; ++i)
        r[i] = static_cast<T>(v ? numberAt(*v, i) : (a.defaultCount > i ? a.defaultNumbers[i] : 0.0));
    return r;
}

std::array<float, 2> SceneAccess::getFloat2(const char* name) { return getTuple<float, 2>(name); }
std::array<float, 3> SceneAccess::getFloat3(const char* name) { return getTuple<float, 3>(name); }
std::array<float, 4> SceneAccess::getFloat4(const char* name) { return getTuple<float, 4>(name); }
std::array<int32_t, 2> SceneAccess::getInt2(const char* name) { return getTuple<int32_t, 2>(name); }

std::string SceneAccess::getToken(const char* name) {
    const auto& a = attribute(name);
    auto v = fetch(a);
    if (v) return static_cast<const char* const*>(v->data)[0];
    return a.defaultToken ? a.defaultToken : "";
}

std::optional<std::string> SceneAccess::getPath(const char* name) {
    auto v = fetch(attribute(name));
    if (!v || v->count == 0) return std::nullopt;
    return std::string(static_cast<const char* const*>(v->data)[0]);
}

std::vector<std::string> SceneAccess::getPathArray(const char* name) {
    auto v = fetch(attribute(name));
    std::vector<std::string> out;
    if (v)
        for (size_t i = 0; i < v->count; ++i) out.emplace_back(static_cast<const char* const*>(v->data)[i]);
    return out;
}

std::optional<std::vector<int32_t>> SceneAccess::getIntArray(const char* name) {
    auto v = fetch(attribute(name));
    if (!v) return std::nullopt;
    const auto* p = static_cast<const int32_t*>(v->data);
    return std::vector<int32_t>(p, p + v->count);
}

std::optional<std::vector<float>> SceneAccess::getFloatArray(const char* name) { return getFloatArrayAt(name, time_); }

std::optional<std::vector<float>> SceneAccess::getFloatArrayAt(const char* name, double time) {
    auto v = fetchAt(attribute(name), time);
    if (!v) return std::nullopt;
    size_t components = v->type == OBSCURA_VALUE_FLOAT4   ? 4
                        : v->type == OBSCURA_VALUE_FLOAT3 ? 3
                        : v->type == OBSCURA_VALUE_FLOAT2 ? 2
                                                          : 1;
    std::vector<float> out(v->count * components);
    for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(numberAt(*v, i));
    return out;
}

ObscuraInterpolation SceneAccess::interpolation(const char* name) {
    const auto& a = attribute(name);
    ObscuraInterpolation out = OBSCURA_INTERPOLATION_VERTEX;
    if (a.interpolation) {
        std::string d = a.interpolation;
        out = d == "constant"      ? OBSCURA_INTERPOLATION_CONSTANT
              : d == "uniform"     ? OBSCURA_INTERPOLATION_UNIFORM
              : d == "varying"     ? OBSCURA_INTERPOLATION_VARYING
              : d == "faceVarying" ? OBSCURA_INTERPOLATION_FACE_VARYING
                                   : OBSCURA_INTERPOLATION_VERTEX;
    }
    if (sd_.getInterpolation) {
        ObscuraInterpolation host{};
        if (sd_.getInterpolation(sd_.userData, path_.c_str(), name, &host) == OBSCURA_OK) {
            if (host < OBSCURA_INTERPOLATION_CONSTANT || host > OBSCURA_INTERPOLATION_FACE_VARYING)
                fail(std::string(name) + ": unknown interpolation " + std::to_string(int(host)));
            out = host;
        }
    }
    return out;
}

Matrix4d interpolateTransform(const std::vector<TransformSample>& samples, double time) {
    if (samples.empty()) return kIdentity;
    if (time <= samples.front().time) return samples.front().matrix;
    for (size_t i = 1; i < samples.size(); ++i)
        if (time <= samples[i].time) {
            const TransformSample &a = samples[i - 1], &b = samples[i];
            double t = b.time > a.time ? (time - a.time) / (b.time - a.time) : 1.0;
            Matrix4d m{};
            for (int k = 0; k < 16; ++k) m[k] = a.matrix[k] + t * (b.matrix[k] - a.matrix[k]);
            return m;
        }
    return samples.back().matrix;
}

std::vector<TransformSample> SceneAccess::sampleTransform(double time0, double time1) {
    constexpr uint32_t kMaxSamples = 16;
    if (!sd_.sampleTransform) return {{time_, kIdentity}};
    double times[kMaxSamples];
    double matrices[kMaxSamples * 16];
    uint32_t count = 0;
    ObscuraStatus s = sd_.sampleTransform(sd_.userData, path_.c_str(), time0, time1, kMaxSamples, times, matrices, &count);
    if (s == OBSCURA_ERROR_NOT_FOUND || (s == OBSCURA_OK && count == 0)) return {{time_, kIdentity}};
    if (s != OBSCURA_OK) fail("the host failed to sample the transform (status " + std::to_string(s) + ")");
    if (count > kMaxSamples) fail("sampleTransform returned more samples than asked for");
    std::vector<TransformSample> out;
    for (uint32_t i = 0; i < count; ++i) {
        TransformSample t{times[i], {}};
        for (int k = 0; k < 16; ++k) {
            t.matrix[k] = matrices[i * 16 + k];
            if (!std::isfinite(t.matrix[k])) fail("transform sample " + std::to_string(i) + " is not finite");
        }
        out.push_back(t);
    }
    return out;
}

}  // namespace obscura::delegate
