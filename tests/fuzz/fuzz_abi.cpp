// libFuzzer target: the C ABI driven by random call sequences and random prim data, against the
// plugin on lavapipe with validation on. Each input is a program: the first bytes pick
// calls (insert, set a value, mark dirty, remove, settings, render, map, stats...), the rest are
// their arguments, decoded with FuzzedDataProvider. Prim types and attribute names come from the
// schema tables, so most values are well-typed and reach the delegate's checks and the frame; a
// fraction are mistyped, non-finite, huge or empty.
//
// A finding is any crash or sanitizer report, a status outside the enum or OBSCURA_ERROR_INTERNAL, a
// NULL lastError, a validation error, or a device or out-of-memory error (no fault is injected, and
// an input of a few kilobytes needs little memory). One delegate serves every input (a device
// per input would cost seconds); each input first removes what the last one inserted and resets
// the render settings, so inputs start from the same empty scene.
#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "schemas/schema.h"
#include "tests/support/in_memory_host.h"

namespace {

using obscura::schema::AttrType;
using obscura::test::HostValue;
using obscura::test::InMemoryHost;

// Paths inputs draw from: a small pool, so calls meet each other's prims; two malformed.
const char* const kPaths[] = {"/Camera", "/Buffers/color", "/Buffers/depth", "/Buffers/id", "/A", "/A/B",
                              "/Looks/m", "/Lights/l", "/World/instancer", "/World/proto", "relative", ""};
const char* const kAovs[] = {"color", "depth", "normal", "primId", "instanceId", "albedo", "bogus"};
const char* const kFormats[] = {"float32Vec4", "float32Vec3", "float32", "int32", "float16Vec4", "bogus"};
constexpr uint64_t kMaxCallsPerInput = 64;
constexpr int kMaxRendersPerInput = 3;

void check(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_abi finding: %s\n", what);
    __builtin_trap();
}

uint64_t abiCalls = 0;  // printed at exit: the closing figure of a long run

void checkStatus(ObscuraStatus s) {
    ++abiCalls;
    check(s >= OBSCURA_OK && s <= OBSCURA_ERROR_INTERNAL, "a status outside ObscuraStatus");
    check(s != OBSCURA_ERROR_INTERNAL, "an internal error");
    check(s != OBSCURA_ERROR_VALIDATION, "a validation error");
    check(s != OBSCURA_ERROR_DEVICE, "a device error without a fault injected");
    check(s != OBSCURA_ERROR_OUT_OF_MEMORY, "out of memory on an input of a few kilobytes");
}

float anyFloat(FuzzedDataProvider& in) {
    switch (in.ConsumeIntegralInRange<int>(0, 7)) {
        case 0: return std::numeric_limits<float>::quiet_NaN();
        case 1: return std::numeric_limits<float>::infinity();
        case 2: return -1e30f;
        case 3: return 0.0f;
        default: return in.ConsumeFloatingPointInRange<float>(-10.0f, 10.0f);
    }
}

int32_t anyInt(FuzzedDataProvider& in) {
    switch (in.ConsumeIntegralInRange<int>(0, 5)) {
        case 0: return in.ConsumeIntegral<int32_t>();
        case 1: return -1;
        default: return in.ConsumeIntegralInRange<int32_t>(0, 12);
    }
}

// Render buffer sizes: small ones that render, and ones the device must refuse (never one that
// fits the device but not this process's memory limit).
int32_t anyDimension(FuzzedDataProvider& in) {
    static const int32_t kRefused[] = {0, -1, 16385, 100000, std::numeric_limits<int32_t>::max()};
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) return kRefused[in.ConsumeIntegralInRange<size_t>(0, 4)];
    return in.ConsumeIntegralInRange<int32_t>(1, 24);
}

// A value of `type` (sometimes of another type), arrays of up to 40 elements.
HostValue anyValue(FuzzedDataProvider& in, AttrType type, const obscura::schema::AttributeSchema& attribute) {
    if (in.ConsumeIntegralInRange<int>(0, 9) == 0) type = static_cast<AttrType>(in.ConsumeIntegralInRange<int>(0, 16));
    const bool array = type >= AttrType::IntArray;
    const size_t count = array ? in.ConsumeIntegralInRange<size_t>(0, 40) : 1;
    HostValue v;
    v.isArray = array;
    v.count = count;
    auto floats = [&](ObscuraValueType t, size_t components) {
        v.type = t;
        for (size_t i = 0; i < count * components; ++i) v.floats.push_back(anyFloat(in));
    };
    auto ints = [&](ObscuraValueType t, size_t components) {
        v.type = t;
        const bool dimensions = std::string(attribute.name) == "dimensions";
        for (size_t i = 0; i < count * components; ++i) v.ints.push_back(dimensions ? anyDimension(in) : anyInt(in));
    };
    auto strings = [&](ObscuraValueType t) {
        v.type = t;
        for (size_t i = 0; i < count; ++i) {
            if (t == OBSCURA_VALUE_PATH || in.ConsumeBool())
                v.strings.push_back(kPaths[in.ConsumeIntegralInRange<size_t>(0, std::size(kPaths) - 1)]);
            else if (attribute.tokenCount > 0 && in.ConsumeBool())
                v.strings.push_back(attribute.tokens[in.ConsumeIntegralInRange<uint32_t>(0, attribute.tokenCount - 1)]);
            else if (std::string(attribute.name) == "format")
                v.strings.push_back(kFormats[in.ConsumeIntegralInRange<size_t>(0, std::size(kFormats) - 1)]);
            else
                v.strings.push_back(in.ConsumeRandomLengthString(24));
        }
    };
    switch (type) {
        case AttrType::Bool: ints(OBSCURA_VALUE_BOOL, 1); break;
        case AttrType::Int: ints(OBSCURA_VALUE_INT, 1); break;
        case AttrType::Float: floats(OBSCURA_VALUE_FLOAT, 1); break;
        case AttrType::Double:
            v.type = OBSCURA_VALUE_DOUBLE;
            v.doubles.push_back(anyFloat(in));
            break;
        case AttrType::Float2: floats(OBSCURA_VALUE_FLOAT2, 2); break;
        case AttrType::Float3: floats(OBSCURA_VALUE_FLOAT3, 3); break;
        case AttrType::Float4: floats(OBSCURA_VALUE_FLOAT4, 4); break;
        case AttrType::Int2: ints(OBSCURA_VALUE_INT2, 2); break;
        case AttrType::Matrix4d:
            v.type = OBSCURA_VALUE_MATRIX4D;
            for (int i = 0; i < 16; ++i) v.doubles.push_back(i % 5 == 0 ? 1.0 : anyFloat(in));
            break;
        case AttrType::Token: strings(OBSCURA_VALUE_TOKEN); break;
        case AttrType::Path: strings(OBSCURA_VALUE_PATH); break;
        case AttrType::IntArray: ints(OBSCURA_VALUE_INT, 1); break;
        case AttrType::FloatArray: floats(OBSCURA_VALUE_FLOAT, 1); break;
        case AttrType::Float2Array: floats(OBSCURA_VALUE_FLOAT2, 2); break;
        case AttrType::Float3Array: floats(OBSCURA_VALUE_FLOAT3, 3); break;
        case AttrType::Float4Array: floats(OBSCURA_VALUE_FLOAT4, 4); break;
        case AttrType::PathArray: strings(OBSCURA_VALUE_PATH); break;
    }
    return v;
}

obscura::test::Matrix anyMatrix(FuzzedDataProvider& in) {
    obscura::test::Matrix m = obscura::test::identity();
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
        case 0: for (double& e : m) e = anyFloat(in); break;   // anything, degenerate and non-finite included
        case 1: m[15] = 0.0; break;                            // projective garbage
        default:                                               // a translation
            m[12] = anyFloat(in), m[13] = anyFloat(in), m[14] = anyFloat(in) - 5.0;
    }
    return m;
}

class AbiProgram {
public:
    AbiProgram(InMemoryHost& host, FuzzedDataProvider& in) : host_(host), api_(host.api()), d_(host.delegate()), in_(in) {}

    void run() {
        // Most programs start from a scene that renders: a camera and a colour buffer.
        if (in_.ConsumeBool()) {
            insert("camera", "/Camera");
            host_.setTransform("/Camera", obscura::test::translation(0, 0, 5));
            host_.set("/Buffers/color", "dimensions", HostValue::int2(anyDimension(in_), anyDimension(in_)));
            host_.set("/Buffers/color", "format", HostValue::token("float32Vec4"));
            insert("renderBuffer", "/Buffers/color");
        }
        for (uint64_t call = 0; call < kMaxCallsPerInput && in_.remaining_bytes() > 0; ++call) step();
    }

    // What this input inserted, for the next one to remove.
    const std::set<std::string>& inserted() const { return inserted_; }

private:
    const char* path() { return kPaths[in_.ConsumeIntegralInRange<size_t>(0, std::size(kPaths) - 1)]; }

    void insert(const char* type, const char* path) {
        ObscuraStatus s = api_.insertPrim(d_, type, path);
        checkStatus(s);
        if (s == OBSCURA_OK) inserted_.insert(path);
    }

    void step() {
        auto schemas = obscura::schema::primSchemas();
        switch (in_.ConsumeIntegralInRange<int>(0, 11)) {
            case 0: {  // insert a prim of a known type (now and then an unknown one)
                const bool unknown = in_.ConsumeIntegralInRange<int>(0, 15) == 0;
                const auto& schema = schemas[in_.ConsumeIntegralInRange<size_t>(0, schemas.size() - 1)];
                insert(unknown ? "bogusType" : schema.name, path());
                break;
            }
            case 1:
            case 2:
            case 3: {  // give an attribute of some prim type a value, then (usually) mark it dirty
                const auto& schema = schemas[in_.ConsumeIntegralInRange<size_t>(0, schemas.size() - 1)];
                if (schema.attributeCount == 0) break;
                const auto& attribute = schema.attributes[in_.ConsumeIntegralInRange<uint32_t>(0, schema.attributeCount - 1)];
                const char* p = path();
                host_.set(p, attribute.name, anyValue(in_, attribute.type, attribute));
                if (in_.ConsumeIntegralInRange<int>(0, 3) != 0) checkStatus(api_.markDirty(d_, p, attribute.dirtyBit));
                break;
            }
            case 4: {  // a transform, marked dirty
                const char* p = path();
                host_.setTransform(p, anyMatrix(in_));
                checkStatus(api_.markDirty(d_, p, OBSCURA_DIRTY_TRANSFORM));
                break;
            }
            case 5: checkStatus(api_.markDirty(d_, path(), in_.ConsumeIntegral<uint32_t>())); break;
            case 6: {
                const char* p = path();
                ObscuraStatus s = api_.removePrim(d_, p);
                checkStatus(s);
                if (s == OBSCURA_OK) inserted_.erase(p);
                break;
            }
            case 7: setting(); break;
            case 8: render(); break;
            case 9: {  // map, read the first and last pixel, and (usually) unmap
                const char* p = path();
                ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
                ObscuraStatus s = api_.mapRenderBuffer(d_, p, &mapped);
                checkStatus(s);
                if (s == OBSCURA_OK && mapped.width > 0 && mapped.height > 0) {
                    check(mapped.data != nullptr, "a mapped buffer without data");
                    const auto* bytes = static_cast<const volatile uint8_t*>(mapped.data);
                    const size_t size = size_t(mapped.rowStride) * (mapped.height - 1) + 1;
                    sink_ ^= bytes[0] ^ bytes[size - 1];
                }
                if (in_.ConsumeIntegralInRange<int>(0, 3) != 0) checkStatus(api_.unmapRenderBuffer(d_, p));
                break;
            }
            case 10: {  // stats with a chain, and timings with any count
                ObscuraMemoryStats memory{OBSCURA_STRUCTURE_TYPE_MEMORY_STATS, nullptr, sizeof(memory)};
                ObscuraRenderStats stats{};
                stats.sType = in_.ConsumeIntegralInRange<int>(0, 7) == 0 ? OBSCURA_STRUCTURE_TYPE_MEMORY_STATS
                                                                          : OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
                stats.pNext = in_.ConsumeBool() ? &memory : nullptr;
                stats.structSize = in_.ConsumeBool() ? sizeof(stats) : in_.ConsumeIntegralInRange<uint32_t>(0, sizeof(stats));
                checkStatus(api_.getRenderStats(d_, &stats));
                std::array<ObscuraPassTiming, 8> timings{};
                uint32_t count = in_.ConsumeIntegralInRange<uint32_t>(0, timings.size());
                checkStatus(api_.getPassTimings(d_, in_.ConsumeBool() ? timings.data() : nullptr, &count));
                break;
            }
            default: {
                int32_t id = 0;
                checkStatus(api_.getPrimId(d_, path(), &id));
            }
        }
        check(api_.lastError(d_) != nullptr, "lastError returned NULL");
    }

    void setting() {
        const char* name = nullptr;
        uint32_t index = in_.ConsumeIntegralInRange<uint32_t>(0, 64);
        if (api_.describeRenderSetting(index, &name, nullptr) != OBSCURA_OK) name = "bogusSetting";
        if (in_.ConsumeIntegralInRange<int>(0, 5) == 0) {
            checkStatus(api_.setRenderSetting(d_, name, nullptr));
            return;
        }
        // Any value type, scalar or a short array.
        ObscuraValue value{static_cast<ObscuraValueType>(in_.ConsumeIntegralInRange<int>(1, 11)), 0, 1, nullptr};
        std::array<double, 16> numbers{};
        std::array<float, 16> floats{};
        std::array<int32_t, 16> ints{};
        std::string token = in_.ConsumeRandomLengthString(16);
        const char* tokens[] = {token.c_str()};
        for (size_t i = 0; i < numbers.size(); ++i) {
            floats[i] = anyFloat(in_);
            numbers[i] = floats[i];
            ints[i] = anyInt(in_);
        }
        switch (value.type) {
            case OBSCURA_VALUE_BOOL:
            case OBSCURA_VALUE_INT:
            case OBSCURA_VALUE_INT2: value.data = ints.data(); break;
            case OBSCURA_VALUE_DOUBLE:
            case OBSCURA_VALUE_MATRIX4D: value.data = numbers.data(); break;
            case OBSCURA_VALUE_TOKEN:
            case OBSCURA_VALUE_PATH: value.data = tokens; break;
            default: value.data = floats.data();
        }
        if (in_.ConsumeIntegralInRange<int>(0, 7) == 0) value.isArray = 1, value.count = in_.ConsumeIntegralInRange<size_t>(0, 1);
        checkStatus(api_.setRenderSetting(d_, name, &value));
    }

    void render() {
        if (renders_++ >= kMaxRendersPerInput) return;
        std::vector<ObscuraAovBinding> bindings;
        const size_t n = in_.ConsumeIntegralInRange<size_t>(0, 3);
        for (size_t i = 0; i < n; ++i)
            bindings.push_back({kAovs[in_.ConsumeIntegralInRange<size_t>(0, std::size(kAovs) - 1)], path()});
        if (bindings.empty() && in_.ConsumeBool()) bindings.push_back({"color", "/Buffers/color"});
        ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC,
                                   nullptr,
                                   sizeof(desc),
                                   in_.ConsumeIntegralInRange<int>(0, 7) == 0 ? path() : "/Camera",
                                   {0, 0, 0, 0},
                                   in_.ConsumeBool() ? 0.0 : double(anyFloat(in_)),
                                   uint32_t(bindings.size()),
                                   bindings.data()};
        if (in_.ConsumeIntegralInRange<int>(0, 7) == 0)  // a viewport without buffers
            desc.viewport[2] = anyDimension(in_), desc.viewport[3] = anyDimension(in_);
        checkStatus(api_.render(d_, &desc));
        ObscuraRenderStats stats{OBSCURA_STRUCTURE_TYPE_RENDER_STATS, nullptr, sizeof(stats)};
        checkStatus(api_.getRenderStats(d_, &stats));
        check(stats.validationErrors == 0, "a validation error");
    }

    InMemoryHost& host_;
    const ObscuraApiV1& api_;
    ObscuraDelegate d_;
    FuzzedDataProvider& in_;
    std::set<std::string> inserted_;
    int renders_ = 0;
    uint8_t sink_ = 0;
};

}  // namespace

namespace {
InMemoryHost* host = nullptr;
}  // namespace

// The delegate is made before the first input, outside libFuzzer's per-input timeout (creating it
// computes the best-fit normals table, slow under the sanitizers).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    host = new InMemoryHost(true);  // validation on; lives as long as the process
    std::atexit([] { std::fprintf(stderr, "fuzz_abi: %llu ABI calls checked\n", (unsigned long long)abiCalls); });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static std::set<std::string> lastInserted;
    InMemoryHost& host = *::host;
    const ObscuraApiV1& api = host.api();
    for (const std::string& path : lastInserted) api.removePrim(host.delegate(), path.c_str());
    for (uint32_t i = 0;; ++i) {
        const char* name = nullptr;
        if (api.describeRenderSetting(i, &name, nullptr) != OBSCURA_OK) break;
        check(api.setRenderSetting(host.delegate(), name, nullptr) == OBSCURA_OK, "a setting does not reset");
    }
    host.forgetScene();
    FuzzedDataProvider in(data, size);
    AbiProgram program(host, in);
    program.run();
    lastInserted = program.inserted();
    return 0;
}
