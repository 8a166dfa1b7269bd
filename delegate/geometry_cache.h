// Identical meshes share one copy on the GPU: repeated references of one asset (a forest of the
// same tree, a set dressed with copies) arrive as separate prims with the same points and
// topology; their vertex and index buffers are found by content and shared, so memory holds the
// mesh once. Entries die with the last prim that uses them.
#pragma once

#include "gpu/device.h"
#include "passes/frame_data.h"

#include <cstdint>
#include <map>
#include <vector>

namespace obscura::delegate {

struct SharedGeometry {
    gpu::BufferPtr vertices;
    gpu::BufferPtr indices;
};

class GeometryCache {
public:
    explicit GeometryCache(gpu::Device& device) : device_(device) {}
    // The buffers holding exactly these vertices and indices, uploaded on first use.
    SharedGeometry get(const std::vector<passes::Vertex>& vertices, const std::vector<uint32_t>& indices,
                       const char* debugName);
    // Bytes of vertex and index data on the GPU, each shared copy counted once.
    uint64_t residentBytes();

private:
    struct Entry {
        std::vector<char> content;  // vertices then indices, compared on a hash hit
        size_t vertexBytes;
        std::weak_ptr<gpu::Buffer> vertices, indices;
    };
    void prune();

    gpu::Device& device_;
    std::multimap<uint64_t, Entry> entries_;
};

}  // namespace obscura::delegate
