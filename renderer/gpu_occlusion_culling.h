// Occlusion culling on the GPU (render setting occlusionCulling with occlusionCulling:route gpu;
// passes/occlusion_cull.h): the G-buffer of a frame whose still draws are culled by compute, in
// two phases around a depth pyramid (passes/hi_z.h): the early culling pass, the early G-buffer
// pass, the pyramid of its depth, the late culling pass, the late G-buffer pass. It keeps each
// instance record's visibility stamp from frame to frame, and the commands host-visible, so that
// what the culling left out is counted once the frame ran.
#pragma once

#include "gpu/frame_backend.h"
#include "gpu/frame_graph.h"
#include "passes/frame_resources.h"
#include "passes/frame_scene.h"

#include <optional>

namespace obscura::renderer {

class GpuOcclusionCulling {
public:
    explicit GpuOcclusionCulling(gpu::FrameBackend& backend) : backend_(backend) {}

    // What the stamps depend on: the instance records they are indexed by.
    struct RecordsKey {
        uint64_t drawnVersion = 0;    // FrameRequest::drawnVersion
        uint64_t settingsVersion = 0;  // FrameRequest::settingsVersion
        uint32_t instanceCount = 0;
        bool operator==(const RecordsKey&) const = default;
    };

    // The G-buffer of `scene`, whose draws with a cullSlot are culled on the GPU.
    passes::GBuffer addGBuffer(gpu::FrameGraph& graph, const passes::FrameScene& scene, const RecordsKey& key,
                               gpu::ImageHandle bestFitNormals, VkSampleCountFlagBits samples, bool alphaToCoverage);

    // Once the frame ran: what the culling left out of `scene`'s culled draws (draws wholly, and
    // their instances and triangles).
    struct Culled {
        uint32_t draws = 0;
        uint64_t instances = 0;
        uint64_t triangles = 0;
    };
    Culled culled(const passes::FrameScene& scene) const;

private:
    // A buffer of at least `bytes`, made again (larger) where it is smaller.
    gpu::BufferPtr& sized(gpu::BufferPtr& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                          gpu::MemoryUsage memory, const char* name);

    gpu::FrameBackend& backend_;
    gpu::BufferPtr stamps_;    // uint per instance record (passes::VisibilityStamps)
    gpu::BufferPtr commands_;  // CulledDrawCommand[2 * culled draws], host-visible
    gpu::BufferPtr lists_;     // uint[2 * candidates]
    gpu::BufferPtr pyramid_;   // float[hiZPyramidFloats]
    uint32_t lastStamp_ = 0;   // the last culled frame's stamp; 0: none
    std::optional<RecordsKey> stamped_;  // what the stamps are indexed by
};

}  // namespace obscura::renderer
