#include "tests/support/in_memory_host.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <stdexcept>

namespace obscura::test {

HostValue HostValue::floatValue(float v) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT;
    h.floats = {v};
    return h;
}
HostValue HostValue::doubleValue(double v) {
    HostValue h;
    h.type = OBSCURA_VALUE_DOUBLE;
    h.doubles = {v};
    return h;
}
HostValue HostValue::float3(float x, float y, float z) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT3;
    h.floats = {x, y, z};
    return h;
}
HostValue HostValue::float2(float x, float y) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT2;
    h.floats = {x, y};
    return h;
}
HostValue HostValue::int2(int32_t x, int32_t y) {
    HostValue h;
    h.type = OBSCURA_VALUE_INT2;
    h.ints = {x, y};
    return h;
}
HostValue HostValue::boolean(bool v) {
    HostValue h;
    h.type = OBSCURA_VALUE_BOOL;
    h.ints = {v ? 1 : 0};
    return h;
}
HostValue HostValue::intValue(int32_t v) {
    HostValue h;
    h.type = OBSCURA_VALUE_INT;
    h.ints = {v};
    return h;
}
HostValue HostValue::token(const std::string& t) {
    HostValue h;
    h.type = OBSCURA_VALUE_TOKEN;
    h.strings = {t};
    return h;
}
HostValue HostValue::path(const std::string& p) {
    HostValue h = token(p);
    h.type = OBSCURA_VALUE_PATH;
    return h;
}
HostValue HostValue::paths(const std::vector<std::string>& p) {
    HostValue h;
    h.type = OBSCURA_VALUE_PATH;
    h.isArray = true;
    h.count = p.size();
    h.strings = p;
    return h;
}
HostValue HostValue::float2Array(const std::vector<std::array<float, 2>>& v) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT2;
    h.isArray = true;
    h.count = v.size();
    for (const auto& e : v) h.floats.insert(h.floats.end(), e.begin(), e.end());
    return h;
}
HostValue HostValue::float4Array(const std::vector<std::array<float, 4>>& v) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT4;
    h.isArray = true;
    h.count = v.size();
    for (const auto& e : v) h.floats.insert(h.floats.end(), e.begin(), e.end());
    return h;
}
HostValue HostValue::points(const std::vector<std::array<float, 3>>& p) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT3;
    h.isArray = true;
    h.count = p.size();
    for (const auto& v : p) h.floats.insert(h.floats.end(), v.begin(), v.end());
    return h;
}
HostValue HostValue::intArray(const std::vector<int32_t>& v) {
    HostValue h;
    h.type = OBSCURA_VALUE_INT;
    h.isArray = true;
    h.count = v.size();
    h.ints = v;
    return h;
}

Matrix identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }
Matrix translation(double x, double y, double z) {
    Matrix m = identity();
    m[12] = x;
    m[13] = y;
    m[14] = z;
    return m;
}

harness::PluginInfo builtPlugin() {
    auto found = harness::discoverPlugins(OBSCURA_TEST_PLUGIN_DIR, {});
    if (found.plugins.empty()) throw std::runtime_error("no plugin in " OBSCURA_TEST_PLUGIN_DIR);
    return found.plugins.front();
}

InMemoryHost::InMemoryHost(bool validation, bool threadSafeCallbacks) {
    auto loaded = harness::loadPlugin(builtPlugin());
    if (auto* error = std::get_if<std::string>(&loaded)) throw std::runtime_error(*error);
    plugin_.emplace(std::move(std::get<harness::LoadedPlugin>(loaded)));
    ObscuraDelegateCreateInfo info{OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO, nullptr, sizeof(info), nullptr,
                                   validation ? 1 : 0, &InMemoryHost::logThunk, this};
    if (api().createDelegate(&info, &delegate_) != OBSCURA_OK)
        throw std::runtime_error(std::string("createDelegate: ") + api().lastError(nullptr));
    sceneDelegate_ = {OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE,
                      nullptr,
                      sizeof(sceneDelegate_),
                      threadSafeCallbacks ? OBSCURA_SCENE_DELEGATE_THREAD_SAFE : 0u,
                      this,
                      &InMemoryHost::getValueThunk, &InMemoryHost::getInterpolationThunk, &InMemoryHost::sampleTransformThunk};
    if (api().setSceneDelegate(delegate_, &sceneDelegate_) != OBSCURA_OK) throw std::runtime_error(lastError());
}

InMemoryHost::~InMemoryHost() {
    if (delegate_) api().destroyDelegate(delegate_);
}

ObscuraStatus InMemoryHost::destroyDelegate() {
    ObscuraStatus s = api().destroyDelegate(delegate_);
    if (s == OBSCURA_OK) delegate_ = nullptr;
    return s;
}

void InMemoryHost::logThunk(void* user, ObscuraLogLevel level, const char* message) {
    auto* self = static_cast<InMemoryHost*>(user);
    {
        std::lock_guard lock(self->counters_);
        self->logThreads.insert(std::this_thread::get_id());
    }
    if (level == OBSCURA_LOG_ERROR) self->errors_.push_back(message);
    if (level == OBSCURA_LOG_WARNING) self->warnings_.push_back(message);
    if (level == OBSCURA_LOG_INFO) self->infos_.push_back(message);
}

void InMemoryHost::addPrim(const std::string& type, const std::string& path, std::map<std::string, HostValue> values,
                       Matrix transform) {
    values_[path] = std::move(values);
    transforms_[path] = transform;
    ObscuraStatus s = api().insertPrim(delegate_, type.c_str(), path.c_str());
    if (s != OBSCURA_OK) throw std::runtime_error("insertPrim " + path + ": " + lastError());
}

void InMemoryHost::set(const std::string& path, const std::string& attribute, HostValue value) {
    values_[path][attribute] = std::move(value);
}

void InMemoryHost::forgetScene() {
    values_.clear();
    interpolations_.clear();
    timeSamples_.clear();
    transforms_.clear();
    motions_.clear();
    errors_.clear();
    warnings_.clear();
    infos_.clear();
    getValueCalls.clear();
    valuesAskedFor.clear();
    callbackThreads.clear();
}

void InMemoryHost::setInterpolation(const std::string& path, const std::string& attribute, ObscuraInterpolation i) {
    interpolations_[path][attribute] = i;
}

void InMemoryHost::setTransform(const std::string& path, Matrix transform) { transforms_[path] = transform; }

void InMemoryHost::setTransformMotion(const std::string& path, double start, Matrix atStart, double end, Matrix atEnd) {
    auto at = [=](double t) {
        double f = std::clamp((t - start) / (end - start), 0.0, 1.0);
        Matrix m;
        for (int k = 0; k < 16; ++k) m[k] = atStart[k] + f * (atEnd[k] - atStart[k]);
        return m;
    };
    motions_[path] = {at, 2};
}

void InMemoryHost::setTransformFunction(const std::string& path, std::function<Matrix(double)> at, uint32_t samples) {
    motions_[path] = {std::move(at), std::max(samples, 2u)};
}

void InMemoryHost::addCamera(const std::string& path, Matrix transform, float focalLength, float aperture) {
    addPrim("camera", path,
            {{"focalLength", HostValue::floatValue(focalLength)},
             {"horizontalAperture", HostValue::floatValue(aperture)},
             {"verticalAperture", HostValue::floatValue(aperture)},
             {"clippingRange", HostValue::float2(0.1f, 1000.0f)}},
            transform);
}

void InMemoryHost::addRenderBuffer(const std::string& path, const std::string& format, int width, int height) {
    addPrim("renderBuffer", path, {{"dimensions", HostValue::int2(width, height)}, {"format", HostValue::token(format)}});
}

ObscuraStatus InMemoryHost::render(const std::string& camera, const std::map<std::string, std::string>& aovs, double time) {
    std::vector<ObscuraAovBinding> bindings;
    for (const auto& [aov, buffer] : aovs) bindings.push_back({aov.c_str(), buffer.c_str()});
    ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(desc), camera.c_str(),
                               {0, 0, 0, 0}, time, static_cast<uint32_t>(bindings.size()), bindings.data()};
    return api().render(delegate_, &desc);
}

std::vector<float> InMemoryHost::readFloats(const std::string& buffer, uint32_t* width, uint32_t* height) {
    ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
    if (api().mapRenderBuffer(delegate_, buffer.c_str(), &m) != OBSCURA_OK) throw std::runtime_error(lastError());
    size_t components = m.format == OBSCURA_FORMAT_FLOAT32_VEC4 ? 4 : m.format == OBSCURA_FORMAT_FLOAT32_VEC3 ? 3 : 1;
    const auto* p = static_cast<const float*>(m.data);
    std::vector<float> out(p, p + size_t(m.width) * m.height * components);
    if (width) *width = m.width;
    if (height) *height = m.height;
    api().unmapRenderBuffer(delegate_, buffer.c_str());
    return out;
}

std::vector<int32_t> InMemoryHost::readInts(const std::string& buffer) {
    ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
    if (api().mapRenderBuffer(delegate_, buffer.c_str(), &m) != OBSCURA_OK) throw std::runtime_error(lastError());
    const auto* p = static_cast<const int32_t*>(m.data);
    std::vector<int32_t> out(p, p + size_t(m.width) * m.height);
    api().unmapRenderBuffer(delegate_, buffer.c_str());
    return out;
}

void InMemoryHost::setTimeSamples(const std::string& path, const std::string& attribute,
                              std::map<double, HostValue> samples) {
    timeSamples_[path][attribute] = std::move(samples);
}

void InMemoryHost::noteCallback(const char* getValuePath, const char* attribute) {
    std::lock_guard lock(counters_);
    if (getValuePath) {
        getValueCalls[getValuePath]++;
        valuesAskedFor.emplace(getValuePath, attribute);
    }
    callbackThreads.insert(std::this_thread::get_id());
}

ObscuraStatus InMemoryHost::getValueThunk(void* user, const char* path, const char* attribute, double time,
                                      ObscuraValue* out) {
    auto* self = static_cast<InMemoryHost*>(user);
    // What this thread handed out last: valid until its next callback (the header's lifetime of a
    // callback's value when callbacks run on several threads).
    thread_local HostValue sampled;
    thread_local std::vector<const char*> stringPointers;
    self->noteCallback(path, attribute);
    if (self->onGetValue) self->onGetValue(path, attribute);
    const HostValue* found = nullptr;
    if (auto prim = self->timeSamples_.find(path); prim != self->timeSamples_.end())
        if (auto it = prim->second.find(attribute); it != prim->second.end() && !it->second.empty()) {
            const auto& samples = it->second;
            auto after = samples.lower_bound(time);
            if (after == samples.end()) {
                found = &std::prev(after)->second;
            } else if (after == samples.begin() || after->first == time) {
                found = &after->second;
            } else {
                auto before = std::prev(after);
                double f = (time - before->first) / (after->first - before->first);
                sampled = before->second;
                for (size_t i = 0; i < sampled.floats.size(); ++i)
                    sampled.floats[i] += float(f) * (after->second.floats[i] - before->second.floats[i]);
                found = &sampled;
            }
        }
    if (!found) {
        auto prim = self->values_.find(path);
        if (prim == self->values_.end()) return OBSCURA_ERROR_NOT_FOUND;
        auto it = prim->second.find(attribute);
        if (it == prim->second.end()) return OBSCURA_ERROR_NOT_FOUND;
        found = &it->second;
    }
    const HostValue& v = *found;
    out->type = v.type;
    out->isArray = v.isArray ? 1 : 0;
    out->count = v.isArray ? v.count : 1;
    switch (v.type) {
        case OBSCURA_VALUE_TOKEN:
        case OBSCURA_VALUE_PATH:
            stringPointers.clear();
            for (const auto& s : v.strings) stringPointers.push_back(s.c_str());
            out->data = stringPointers.data();
            break;
        case OBSCURA_VALUE_BOOL:
        case OBSCURA_VALUE_INT:
        case OBSCURA_VALUE_INT2: out->data = v.ints.data(); break;
        case OBSCURA_VALUE_DOUBLE:
        case OBSCURA_VALUE_MATRIX4D: out->data = v.doubles.data(); break;
        default: out->data = v.floats.data(); break;
    }
    return OBSCURA_OK;
}

ObscuraStatus InMemoryHost::getInterpolationThunk(void* user, const char* path, const char* attribute,
                                              ObscuraInterpolation* out) {
    auto* self = static_cast<InMemoryHost*>(user);
    self->noteCallback(nullptr);
    auto prim = self->interpolations_.find(path);
    if (prim == self->interpolations_.end()) return OBSCURA_ERROR_NOT_FOUND;
    auto it = prim->second.find(attribute);
    if (it == prim->second.end()) return OBSCURA_ERROR_NOT_FOUND;
    *out = it->second;
    return OBSCURA_OK;
}

ObscuraStatus InMemoryHost::sampleTransformThunk(void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                             double* times, double* matrices, uint32_t* count) {
    auto* self = static_cast<InMemoryHost*>(user);
    self->noteCallback(nullptr);
    if (auto motion = self->motions_.find(path); motion != self->motions_.end() && maxSamples >= 2) {
        const Motion& m = motion->second;
        uint32_t n = t1 > t0 ? std::min(m.samples, maxSamples) : 1;
        for (uint32_t i = 0; i < n; ++i) {
            double t = n == 1 ? t0 : t0 + (t1 - t0) * i / (n - 1);
            times[i] = t;
            Matrix at = m.at(t);
            std::memcpy(matrices + i * 16, at.data(), sizeof(double) * 16);
        }
        *count = n;
        return OBSCURA_OK;
    }
    auto it = self->transforms_.find(path);
    if (it == self->transforms_.end() || maxSamples == 0) return OBSCURA_ERROR_NOT_FOUND;
    times[0] = t0;
    std::memcpy(matrices, it->second.data(), sizeof(double) * 16);
    *count = 1;
    return OBSCURA_OK;
}

}  // namespace obscura::test
