// Typed, schema-checked pulls from the host's scene delegate for one prim during sync.
// Unauthored attributes get the schema default; a value of the wrong type, shape or with
// NaN/Inf is bad prim data: it throws PrimDataError, and the delegate skips the prim.
#pragma once

#include "renderer/matrix.h"
#include "schemas/schema.h"

#include <obscura/obscura.h>

#include <array>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace obscura::delegate {

struct PrimDataError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct TransformSample {
    double time;
    Matrix4d matrix;
};

// The transform at `time` from samples sorted by time: linear between the two around it (as
// Hydra's HdResampleNeighbors), the first or last outside them; identity without samples.
Matrix4d interpolateTransform(const std::vector<TransformSample>& samples, double time);

class SceneAccess {
public:
    // `dirty`: the bits this sync pulls (all of them for a prim seen the first time).
    SceneAccess(const ObscuraSceneDelegate& sceneDelegate, const schema::PrimSchema& schema, const std::string& path,
                double time, ObscuraDirtyBits dirty = OBSCURA_DIRTY_ALL);

    double time() const { return time_; }
    const std::string& path() const { return path_; }

    // Whether this sync reads `name` again: its dirty bit is among those marked. The schemas
    // (schemas/*.json) are the one owner of which bit re-reads which attribute.
    bool dirty(const char* name) const;
    bool anyDirty(std::initializer_list<const char*> names) const;
    bool anyDirty() const { return anyDirtyBut({}); }  // any attribute of the prim's schema
    // Whether any attribute of the prim's schema other than `except` is.
    bool anyDirtyBut(std::initializer_list<const char*> except) const;

    bool getBool(const char* name);
    int32_t getInt(const char* name);
    double getDouble(const char* name);  // float or double attributes
    float getFloat(const char* name) { return static_cast<float>(getDouble(name)); }
    std::array<float, 2> getFloat2(const char* name);
    std::array<float, 3> getFloat3(const char* name);
    std::array<float, 4> getFloat4(const char* name);
    std::array<int32_t, 2> getInt2(const char* name);
    std::string getToken(const char* name);
    std::optional<std::string> getPath(const char* name);  // empty when unauthored
    std::vector<std::string> getPathArray(const char* name);  // empty when unauthored
    // Arrays: nullopt when not authored.
    std::optional<std::vector<int32_t>> getIntArray(const char* name);
    std::optional<std::vector<float>> getFloatArray(const char* name);  // float[] and floatN[] flattened
    // The same at another time (the shutter's ends, for motion blur).
    std::optional<std::vector<float>> getFloatArrayAt(const char* name, double time);
    ObscuraInterpolation interpolation(const char* name);

    // World transform samples over [time0, time1] (at least one).
    std::vector<TransformSample> sampleTransform(double time0, double time1);

private:
    // A fixed-size numeric value (float2/3/4, int2), or the schema default.
    template <typename T, size_t N>
    std::array<T, N> getTuple(const char* name);
    // The host's value, checked against the schema; nullopt when not authored.
    std::optional<ObscuraValue> fetch(const schema::AttributeSchema& attribute);
    std::optional<ObscuraValue> fetchAt(const schema::AttributeSchema& attribute, double time);
    const schema::AttributeSchema& attribute(const char* name) const;
    [[noreturn]] void fail(const std::string& message) const;

    const ObscuraSceneDelegate& sd_;
    const schema::PrimSchema& schema_;
    std::string path_;
    double time_;
    ObscuraDirtyBits dirty_;
};

}  // namespace obscura::delegate
