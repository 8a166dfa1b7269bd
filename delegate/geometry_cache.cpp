#include "delegate/geometry_cache.h"

#include <xxhash.h>

#include <new>

namespace obscura::delegate {
namespace {

template <typename T>
size_t byteSize(const std::vector<T>& values) {
    return values.size() * sizeof(T);
}

}  // namespace

ContentKeyBuilder::ContentKeyBuilder() : state_(XXH3_createState()) {
    if (!state_) throw std::bad_alloc();
    XXH3_128bits_reset(state_);
}

ContentKeyBuilder::~ContentKeyBuilder() { XXH3_freeState(state_); }

void ContentKeyBuilder::add(const void* data, size_t bytes) { XXH3_128bits_update(state_, data, bytes); }

ContentKey ContentKeyBuilder::key() const {
    const XXH128_hash_t hash = XXH3_128bits_digest(state_);
    return {hash.low64, hash.high64};
}

GeometryContent geometryContent(std::vector<passes::Vertex> vertices, std::vector<uint32_t> indices) {
    GeometryContent c{std::move(vertices), std::move(indices), {}};
    // The vertices' count first: where the vertices end and the indices begin is content too.
    ContentKeyBuilder key;
    key.addArray(c.vertices);
    key.add(c.indices.data(), byteSize(c.indices));
    c.hash = key.key();
    return c;
}

SharedGeometry GeometryCache::get(const GeometryContent& content, const char* debugName) {
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

std::shared_ptr<BuiltMesh> builtMesh(MeshGeometry&& geometry) {
    auto built = std::make_shared<BuiltMesh>();
    built->groupRanges = std::move(geometry.groupRanges);
    built->warnings = std::move(geometry.warnings);
    for (const passes::Vertex& v : geometry.vertices) {
        built->bounds.extend({v.position[0], v.position[1], v.position[2]});
        built->translucentVertices = built->translucentVertices || v.color[3] < 1.0f;
    }
    built->vertexCount = geometry.vertices.size();
    built->indexCount = static_cast<uint32_t>(geometry.indices.size());
    built->content = geometryContent(std::move(geometry.vertices), std::move(geometry.indices));
    return built;
}

std::shared_ptr<BuiltMesh> BuiltMeshCache::find(const ContentKey& key) {
    std::lock_guard lock(mutex_);
    auto it = entries_.find(key);
    return it == entries_.end() ? nullptr : it->second.lock();
}

std::shared_ptr<BuiltMesh> BuiltMeshCache::insert(const ContentKey& key, std::shared_ptr<BuiltMesh> built) {
    std::lock_guard lock(mutex_);
    std::weak_ptr<BuiltMesh>& entry = entries_[key];
    if (auto first = entry.lock()) return first;
    entry = built;
    return built;
}

void BuiltMeshCache::prune() {
    std::lock_guard lock(mutex_);
    std::erase_if(entries_, [](const auto& entry) { return entry.second.expired(); });
}

}  // namespace obscura::delegate
