// An in-memory Hydra host: prims with attribute values held in maps, served through the
// scene-delegate callbacks, with every callback counted. The plugin is loaded through plugInfo.json
// discovery exactly as the harness does; every logged message is kept. Delegate tests use it through
// TestHost (tests/support/test_host.h), which fails a test on an error it did not declare; the
// fuzz target and the benchmarks use it as it is.
#pragma once

#include "harness/plugin_loader.h"

#include <obscura/obscura.h>

#include <array>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace obscura::test {

struct HostValue {
    ObscuraValueType type = OBSCURA_VALUE_NONE;
    bool isArray = false;
    std::vector<float> floats;
    std::vector<double> doubles;
    std::vector<int32_t> ints;
    std::vector<std::string> strings;
    size_t count = 1;

    static HostValue floatValue(float v);
    static HostValue doubleValue(double v);
    static HostValue float3(float x, float y, float z);
    static HostValue float2(float x, float y);
    static HostValue int2(int32_t x, int32_t y);
    static HostValue boolean(bool v);
    static HostValue intValue(int32_t v);
    static HostValue token(const std::string& t);
    static HostValue path(const std::string& p);
    static HostValue paths(const std::vector<std::string>& p);
    static HostValue float2Array(const std::vector<std::array<float, 2>>& v);
    static HostValue float4Array(const std::vector<std::array<float, 4>>& v);
    static HostValue points(const std::vector<std::array<float, 3>>& p);
    static HostValue intArray(const std::vector<int32_t>& v);
};

using Matrix = std::array<double, 16>;
Matrix translation(double x, double y, double z);
Matrix identity();

class InMemoryHost {
public:
    // `threadSafeCallbacks`: the scene delegate declares OBSCURA_SCENE_DELEGATE_THREAD_SAFE (its
    // callbacks only read the maps; counters are locked), so sync may call it from several threads.
    explicit InMemoryHost(bool validation = true, bool threadSafeCallbacks = false);
    ~InMemoryHost();
    InMemoryHost(const InMemoryHost&) = delete;
    InMemoryHost& operator=(const InMemoryHost&) = delete;

    const ObscuraApiV1& api() const { return plugin_->api(); }
    ObscuraDelegate delegate() const { return delegate_; }
    // The scene delegate this host installed.
    const ObscuraSceneDelegate& sceneDelegate() const { return sceneDelegate_; }

    // Inserts the prim into the delegate and records its values here.
    void addPrim(const std::string& type, const std::string& path, std::map<std::string, HostValue> values = {},
                 Matrix transform = identity());
    void set(const std::string& path, const std::string& attribute, HostValue value);
    void setInterpolation(const std::string& path, const std::string& attribute, ObscuraInterpolation interpolation);
    // Time samples of an attribute: float values interpolate linearly between them (as USD's),
    // held before the first and after the last; they win over the value set().
    void setTimeSamples(const std::string& path, const std::string& attribute, std::map<double, HostValue> samples);
    void setTransform(const std::string& path, Matrix transform);
    // A transform moving linearly from `atStart` at time `start` to `atEnd` at `end` (held outside):
    // sampleTransform then answers with the interval's two ends, as a host with time samples does.
    void setTransformMotion(const std::string& path, double start, Matrix atStart, double end, Matrix atEnd);
    // A transform given by a function of time: sampleTransform answers with `samples` evenly spaced
    // samples over the interval asked for (a host with that many time samples in it).
    void setTransformFunction(const std::string& path, std::function<Matrix(double)> at, uint32_t samples);

    // Convenience scene pieces.
    void addCamera(const std::string& path, Matrix transform, float focalLength = 50.0f, float aperture = 20.955f);
    void addRenderBuffer(const std::string& path, const std::string& format, int width, int height);

    // Renders `aovs` (aov -> render buffer path) from `camera`.
    ObscuraStatus render(const std::string& camera, const std::map<std::string, std::string>& aovs, double time = 0.0);
    // Copies a rendered buffer out (floats for float formats, ints for int32).
    std::vector<float> readFloats(const std::string& buffer, uint32_t* width = nullptr, uint32_t* height = nullptr);
    std::vector<int32_t> readInts(const std::string& buffer);

    std::string lastError() const { return api().lastError(delegate_); }
    // Destroys the delegate now (the host keeps its logs), so a test can see what destruction logged.
    ObscuraStatus destroyDelegate();
    const std::vector<std::string>& loggedErrors() const { return errors_; }
    const std::vector<std::string>& loggedWarnings() const { return warnings_; }
    const std::vector<std::string>& loggedInfos() const { return infos_; }
    // getValue callbacks per prim path since the last reset, and the (path, attribute) pairs asked for.
    std::map<std::string, int> getValueCalls;
    std::set<std::pair<std::string, std::string>> valuesAskedFor;
    // The threads scene-delegate callbacks ran on since the last reset.
    std::set<std::thread::id> callbackThreads;
    // The threads log callbacks ran on.
    std::set<std::thread::id> logThreads;
    // Called inside every getValue callback (path, attribute), before it answers: a host that calls
    // back into the API from its callbacks.
    std::function<void(const std::string&, const std::string&)> onGetValue;
    void resetCounters() {
        getValueCalls.clear();
        valuesAskedFor.clear();
        callbackThreads.clear();
    }
    // Forgets every value, transform and log this host holds (the delegate's prims stay): a fuzz
    // input starts from a host that knows nothing.
    void forgetScene();

private:
    // Counts a callback on this thread (a getValue of `getValuePath`'s `attribute` when not null).
    void noteCallback(const char* getValuePath, const char* attribute = nullptr);
    static void logThunk(void* user, ObscuraLogLevel level, const char* message);
    static ObscuraStatus getValueThunk(void* user, const char* path, const char* attribute, double time,
                                       ObscuraValue* out);
    static ObscuraStatus getInterpolationThunk(void* user, const char* path, const char* attribute,
                                               ObscuraInterpolation* out);
    static ObscuraStatus sampleTransformThunk(void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                              double* times, double* matrices, uint32_t* count);

    std::optional<harness::LoadedPlugin> plugin_;
    ObscuraDelegate delegate_ = nullptr;
    ObscuraSceneDelegate sceneDelegate_{};
    std::map<std::string, std::map<std::string, HostValue>> values_;
    std::map<std::string, std::map<std::string, ObscuraInterpolation>> interpolations_;
    std::map<std::string, std::map<std::string, std::map<double, HostValue>>> timeSamples_;
    std::mutex counters_;  // getValueCalls, callbackThreads and logThreads: written from every calling thread
    std::map<std::string, Matrix> transforms_;
    struct Motion {
        std::function<Matrix(double)> at;
        uint32_t samples;
    };
    std::map<std::string, Motion> motions_;
    std::vector<std::string> errors_;
    std::vector<std::string> warnings_;
    std::vector<std::string> infos_;
};

// The plugin as the test build made it (discovered through its plugInfo.json).
harness::PluginInfo builtPlugin();

}  // namespace obscura::test
