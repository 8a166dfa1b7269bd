// Occlusion culling on the GPU (render setting occlusionCulling with occlusionCulling:route gpu;
// passes/occlusion_cull.h): the G-buffer and the shadow maps of a frame whose still draws are
// culled by compute, each in two phases around a depth pyramid (passes/hi_z.h): the early culling
// pass, the early raster pass, the pyramid of its depth, the late culling pass, the late raster
// pass. It keeps the visibility stamps from frame to frame (per instance record for the camera,
// per shadow view and record for the atlas). The commands start each frame from the host's and are
// counted into device-local memory; the camera's go back to the host, so that what the culling
// left out is counted once the frame ran.
#pragma once

#include "gpu/frame_backend.h"
#include "gpu/frame_graph.h"
#include "passes/frame_resources.h"
#include "passes/frame_scene.h"
#include "passes/occlusion_cull.h"
#include "passes/shadow_maps.h"

#include <optional>
#include <vector>

namespace obscura::renderer {

class GpuOcclusionCulling {
public:
    explicit GpuOcclusionCulling(gpu::FrameBackend& backend) : backend_(backend) {}

    // What the stamps are indexed by besides the records' count: a change to what is drawn or to a
    // setting may renumber the records.
    struct Versions {
        uint64_t drawnVersion = 0;    // FrameRequest::drawnVersion
        uint64_t settingsVersion = 0;  // FrameRequest::settingsVersion
        bool operator==(const Versions&) const = default;
    };

    // The G-buffer of `scene`, whose draws with a cullSlot are culled on the GPU.
    passes::GBuffer addGBuffer(gpu::FrameGraph& graph, const passes::FrameScene& scene, const Versions& versions,
                               gpu::ImageHandle bestFitNormals, VkSampleCountFlagBits samples, bool alphaToCoverage);
    // The shadow atlas of `scene`, whose views' culled draws (CulledViewDraw) are culled on the GPU.
    gpu::ImageHandle addShadowMaps(gpu::FrameGraph& graph, const passes::FrameScene& scene, const Versions& versions,
                                   passes::ShadowAtlasHistory& history);

    // Once the frame ran: what the culling left out of `scene`'s culled camera draws (draws wholly,
    // and their instances and triangles).
    struct Culled {
        uint32_t draws = 0;
        uint64_t instances = 0;
        uint64_t triangles = 0;
    };
    Culled culled(const passes::FrameScene& scene) const;

private:
    // One culled view's buffers (the camera's, the atlas's) and its stamps' history.
    struct Route {
        gpu::BufferPtr stamps;    // uint per stamp (passes::VisibilityStamps)
        gpu::BufferPtr commands;  // CulledDrawCommand[2 * culled draws], device-local
        gpu::BufferPtr counted;   // the camera's commands once the frame ran, host-visible
        gpu::BufferPtr lists;     // uint[2 * candidates]
        gpu::BufferPtr pyramid;   // float[hiZPyramidFloats]
        uint32_t lastStamp = 0;   // the last culled frame's stamp; 0: none
        struct Key {
            Versions versions;
            uint64_t stampCount = 0;
            bool operator==(const Key&) const = default;
        };
        std::optional<Key> stamped;  // what the stamps are indexed by
    };
    // Imports `route`'s buffers into `graph` for a frame of `commands` (the early phase's; the late
    // phase's are written alike) and `stamps` stamps, and adds the early culling pass; `pyramid`
    // gets the pyramid of a `width` x `height` depth.
    passes::CulledDraws addEarlyCulling(gpu::FrameGraph& graph, const passes::FrameScene& scene, Route& route,
                                        passes::CulledDraws culled, const std::vector<passes::CulledDrawCommand>& commands,
                                        const Route::Key& key, passes::VisibilityStamps& stamps,
                                        uint32_t width, uint32_t height, gpu::BufferHandle& pyramid);
    // A buffer of at least `bytes`, made again (larger) where it is smaller.
    gpu::BufferPtr& sized(gpu::BufferPtr& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                          gpu::MemoryUsage memory, const char* name);

    gpu::FrameBackend& backend_;
    Route camera_, shadows_;
};

}  // namespace obscura::renderer
