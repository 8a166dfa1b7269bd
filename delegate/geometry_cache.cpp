#include "delegate/geometry_cache.h"

#include <xxhash.h>

namespace obscura::delegate {
namespace {

template <typename T>
size_t byteSize(const std::vector<T>& values) {
    return values.size() * sizeof(T);
}

}  // namespace

GeometryContent geometryContent(std::vector<passes::Vertex> vertices, std::vector<uint32_t> indices) {
    GeometryContent c{std::move(vertices), std::move(indices), {}};
    // The vertices' byte count first: where the vertices end and the indices begin is content too.
    const uint64_t vertexBytes = byteSize(c.vertices);
    XXH3_state_t* state = XXH3_createState();
    XXH3_128bits_reset(state);
    XXH3_128bits_update(state, &vertexBytes, sizeof(vertexBytes));
    XXH3_128bits_update(state, c.vertices.data(), byteSize(c.vertices));
    XXH3_128bits_update(state, c.indices.data(), byteSize(c.indices));
    const XXH128_hash_t hash = XXH3_128bits_digest(state);
    XXH3_freeState(state);
    c.hash = {hash.low64, hash.high64};
    return c;
}

SharedGeometry GeometryCache::get(GeometryContent content, const char* debugName) {
    if (auto it = entries_.find(content.hash); it != entries_.end()) {
        SharedGeometry shared{it->second.vertices.lock(), it->second.indices.lock()};
        if (shared.vertices && shared.indices) return shared;
    }
    gpu::MemoryCategoryScope geometry(gpu::MemoryCategory::Geometry);
    SharedGeometry created{device_.createBufferWithData(content.vertices.data(), byteSize(content.vertices),
                                                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, debugName),
                           device_.createBufferWithData(content.indices.data(), byteSize(content.indices),
                                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT, debugName)};
    entries_.insert_or_assign(content.hash,
                              Entry{byteSize(content.vertices) + byteSize(content.indices), created.vertices, created.indices});
    return created;
}

uint64_t GeometryCache::residentBytes() {
    prune();
    uint64_t bytes = 0;
    for (const auto& [key, entry] : entries_) bytes += entry.bytes;
    return bytes;
}

void GeometryCache::prune() {
    for (auto it = entries_.begin(); it != entries_.end();)
        it = it->second.vertices.expired() ? entries_.erase(it) : std::next(it);
}

}  // namespace obscura::delegate
