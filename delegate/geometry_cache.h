// Identical meshes share one copy on the GPU: repeated references of one asset (a forest of the
// same tree, a set dressed with copies) arrive as separate prims with the same points and
// topology; their vertex and index buffers are found by content and shared, so memory holds the
// mesh once. Entries die with the last prim that uses them.
#pragma once

#include "gpu/device.h"
#include "passes/frame_data.h"

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace obscura::delegate {

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
    std::array<uint64_t, 2> hash{};
};
GeometryContent geometryContent(std::vector<passes::Vertex> vertices, std::vector<uint32_t> indices);

class GeometryCache {
public:
    explicit GeometryCache(gpu::Device& device) : device_(device) {}
    // The buffers holding exactly this content, uploaded on first use.
    SharedGeometry get(GeometryContent content, const char* debugName);
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
    std::map<std::array<uint64_t, 2>, Entry> entries_;
};

}  // namespace obscura::delegate
