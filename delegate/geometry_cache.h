// Identical meshes share one copy on the GPU: repeated references of one asset (a forest of the
// same tree, a set dressed with copies) arrive as separate prims with the same points and
// topology; their vertex and index buffers are found by content and shared, so memory holds the
// mesh once. Entries die with the last prim that uses them. Prims whose inputs are equal are also
// refined and built once (BuiltMeshCache).
#pragma once

#include "delegate/bounds.h"
#include "delegate/mesh_builder.h"
#include "gpu/device.h"
#include "passes/frame_data.h"

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

struct XXH3_state_s;

namespace obscura::delegate {

// An XXH3-128 key over what is added to it (bulk data: a collision is trusted not to happen).
using ContentKey = std::array<uint64_t, 2>;
class ContentKeyBuilder {
public:
    ContentKeyBuilder();
    ~ContentKeyBuilder();
    ContentKeyBuilder(const ContentKeyBuilder&) = delete;
    ContentKeyBuilder& operator=(const ContentKeyBuilder&) = delete;
    void add(const void* data, size_t bytes);
    template <typename T>
    void add(const T& value) {
        add(&value, sizeof(T));
    }
    // An array with its element count first, so that where one ends is part of the key.
    template <typename T>
    void addArray(const std::vector<T>& values) {
        add(uint64_t(values.size()));
        add(values.data(), values.size() * sizeof(T));
    }
    ContentKey key() const;

private:
    XXH3_state_s* state_;
};

struct SharedGeometry {
    gpu::BufferPtr vertices;
    gpu::BufferPtr indices;
};

// A mesh's drawn vertices and indices as the cache keys them: made where the geometry is built
// (on any thread, as parallel sync's pulls are), looked up on the thread that owns the device.
// They are the built geometry's own arrays, moved in and freed once uploaded. The key is their
// XXH3-128 hash, trusted as the texture disk cache trusts it: no copy of a scene's meshes is kept
// on the CPU to confirm a hit (two different meshes share a hash with a chance of 2^-128).
struct GeometryContent {
    std::vector<passes::Vertex> vertices;
    std::vector<uint32_t> indices;
    ContentKey hash{};
};
GeometryContent geometryContent(std::vector<passes::Vertex> vertices, std::vector<uint32_t> indices);

class GeometryCache {
public:
    explicit GeometryCache(gpu::Device& device) : device_(device) {}
    // The buffers holding exactly this content, uploaded on first use.
    SharedGeometry get(const GeometryContent& content, const char* debugName);
    // Bytes of vertex and index data on the GPU, each shared copy counted once.
    uint64_t residentBytes();
    // Forgets the entries whose last user has gone (once per sync: a lookup skips them).
    void prune();

private:
    struct Entry {
        uint64_t bytes;
        std::weak_ptr<gpu::Buffer> vertices, indices;
    };

    gpu::Device& device_;
    std::map<ContentKey, Entry> entries_;
};

// A mesh as built for drawing (refined, triangulated, welded), shared by the prims whose inputs
// are equal: what each keeps on the CPU, and on the thread that owns the device the content until
// its first upload, then the buffers.
struct BuiltMesh {
    std::vector<IndexRange> groupRanges;
    std::vector<std::string> warnings;  // without the prim's path
    Aabb bounds;
    bool translucentVertices = false;  // some vertex's displayOpacity is below 1
    size_t vertexCount = 0;
    uint32_t indexCount = 0;
    GeometryContent content;
    SharedGeometry buffers;
};
std::shared_ptr<BuiltMesh> builtMesh(MeshGeometry&& geometry);

// Built meshes by the key of what they were built from (the prim's points, topology, primvars,
// face groups and refinement): a prim whose inputs equal another's, a repeated reference of one
// asset, skips refinement and building. Entries live while a prim holds them. Thread-safe: pulls
// run on several threads at once under parallel sync.
class BuiltMeshCache {
public:
    std::shared_ptr<BuiltMesh> find(const ContentKey& key);
    // Caches `built` under `key`, unless another pull cached one first: the one cached is returned.
    std::shared_ptr<BuiltMesh> insert(const ContentKey& key, std::shared_ptr<BuiltMesh> built);
    // Forgets the entries no prim holds any more.
    void prune();

private:
    std::mutex mutex_;
    std::map<ContentKey, std::weak_ptr<BuiltMesh>> entries_;
};

}  // namespace obscura::delegate
