#include "delegate/geometry_cache.h"

#include <cstring>

#include "gpu/content_hash.h"

namespace obscura::delegate {

SharedGeometry GeometryCache::get(const std::vector<passes::Vertex>& vertices, const std::vector<uint32_t>& indices,
                                  const char* debugName) {
    prune();
    size_t vertexBytes = vertices.size() * sizeof(passes::Vertex), indexBytes = indices.size() * sizeof(uint32_t);
    std::vector<char> content(vertexBytes + indexBytes);
    if (vertexBytes) std::memcpy(content.data(), vertices.data(), vertexBytes);
    if (indexBytes) std::memcpy(content.data() + vertexBytes, indices.data(), indexBytes);
    // A hit is confirmed by comparing the bytes.
    uint64_t key = gpu::hashBytes(content.data(), content.size(), gpu::hashValue(vertexBytes, gpu::kContentHashSeed));
    auto [first, last] = entries_.equal_range(key);
    for (auto it = first; it != last; ++it) {
        if (it->second.vertexBytes != vertexBytes || it->second.content != content) continue;
        SharedGeometry shared{it->second.vertices.lock(), it->second.indices.lock()};
        if (shared.vertices && shared.indices) return shared;
    }
    SharedGeometry created{
        device_.createBufferWithData(vertices.data(), vertexBytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, debugName),
        device_.createBufferWithData(indices.data(), indexBytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, debugName)};
    entries_.emplace(key, Entry{std::move(content), vertexBytes, created.vertices, created.indices});
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
