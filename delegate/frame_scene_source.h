// The frame's scene as the renderer asks for it (renderer::FrameSceneSource): the synced prims
// packed by buildFrameScene for each viewpoint, and what the frame could not honour reported to
// the host once per change.
#pragma once

#include "delegate/frame_scene_builder.h"
#include "gpu/log.h"
#include "renderer/frame_renderer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace obscura::delegate {

// What the last frame's scene held and lacked, kept from frame to frame so that a shortfall is
// logged when it changes, not every frame.
struct FrameSceneReport {
    uint64_t trianglesDrawn = 0;
    passes::CullingCounts culling;
    uint32_t lightsWithoutShadowRoom = 0;
    std::vector<std::string> unclippedLights;
    std::vector<std::string> unresolvedSubsetMaterials;
};

class FrameSceneSource final : public renderer::FrameSceneSource {
public:
    // `frame`: the prims and settings; its viewpoint is replaced by each one asked for.
    FrameSceneSource(gpu::Device& device, const FrameSceneInputs& frame, FrameSceneReport& report, const LogSink& log)
        : device_(device), frame_(frame), report_(report), log_(log) {}

    renderer::FrameView view(const renderer::FrameViewpoint& viewpoint) const override;
    // Throws ApiError (OUT_OF_MEMORY) for more instances than the G-buffer addresses.
    passes::FrameScene scene(const renderer::FrameViewpoint& viewpoint) override;
    void culledOnGpu(uint32_t draws, uint64_t instances, uint64_t triangles) override;

private:
    FrameSceneInputs inputs(const renderer::FrameViewpoint& viewpoint) const;
    void report(const passes::FrameScene& scene, const FrameSceneShortfalls& shortfalls);

    gpu::Device& device_;
    const FrameSceneInputs& frame_;
    FrameSceneReport& report_;
    const LogSink& log_;
};

}  // namespace obscura::delegate
