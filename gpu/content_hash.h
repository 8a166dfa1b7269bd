// FNV-1a over bytes: equal content, equal key. Small records key on it (the kept shadow atlas's
// views, the pipeline cache file's check); where a collision would be wrong rather than slow, the
// caller confirms with the bytes. Bulk data (geometry, textures) is keyed by XXH3-128.
#pragma once

#include <cstddef>
#include <cstdint>

namespace obscura::gpu {

constexpr uint64_t kContentHashSeed = 1469598103934665603ull;

inline uint64_t hashBytes(const void* data, size_t size, uint64_t h = kContentHashSeed) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
}

template <typename T>
uint64_t hashValue(const T& value, uint64_t h) {
    return hashBytes(&value, sizeof(T), h);
}

}  // namespace obscura::gpu
