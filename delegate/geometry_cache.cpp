#include "delegate/geometry_cache.h"

#include <cstring>

#include "gpu/content_hash.h"

namespace obscura::delegate {

GeometryContent geometryContent(const std::vector<passes::Vertex>& vertices, const std::vector<uint32_t>& indices) {
    GeometryContent c;
    c.vertexBytes = vertices.size() * sizeof(passes::Vertex);
    const size_t indexBytes = indices.size() * sizeof(uint32_t);
    c.bytes.resize(c.vertexBytes + indexBytes);
    if (c.vertexBytes) std::memcpy(c.bytes.data(), vertices.data(), c.vertexBytes);
    if (indexBytes) std::memcpy(c.bytes.data() + c.vertexBytes, indices.data(), indexBytes);
    c.hash = gpu::hashBytes(c.bytes.data(), c.bytes.size(), gpu::hashValue(c.vertexBytes, gpu::kContentHashSeed));
    return c;
}

SharedGeometry GeometryCache::get(GeometryContent content, const char* debugName) {
    // A hit is confirmed by comparing the bytes.
    auto [first, last] = entries_.equal_range(content.hash);
    for (auto it = first; it != last; ++it) {
        if (it->second.vertexBytes != content.vertexBytes || it->second.content != content.bytes) continue;
        SharedGeometry shared{it->second.vertices.lock(), it->second.indices.lock()};
        if (shared.vertices && shared.indices) return shared;
    }
    const size_t indexBytes = content.bytes.size() - content.vertexBytes;
    gpu::MemoryCategoryScope geometry(gpu::MemoryCategory::Geometry);
    SharedGeometry created{device_.createBufferWithData(content.bytes.data(), content.vertexBytes,
                                                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, debugName),
                           device_.createBufferWithData(content.bytes.data() + content.vertexBytes, indexBytes,
                                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT, debugName)};
    entries_.emplace(content.hash, Entry{std::move(content.bytes), content.vertexBytes, created.vertices, created.indices});
    return created;
}

uint64_t GeometryCache::residentBytes() {
    prune();
    uint64_t bytes = 0;
    for (const auto& [key, entry] : entries_) bytes += entry.content.size();
    return bytes;
}

void GeometryCache::prune() {
    for (auto it = entries_.begin(); it != entries_.end();)
        it = it->second.vertices.expired() ? entries_.erase(it) : std::next(it);
}

}  // namespace obscura::delegate
