// Shadow maps (frame step 3, before the G-buffer): depth-only rendering of the scene's draws into
// every view of the frame's shadow atlas (FrameScene::shadows), one tile per view. The lighting
// pass filters the atlas per pixel (shaders/common/shadow_sampling.glsl).
#pragma once

#include "gpu/frame_graph.h"
#include "gpu/history_images.h"
#include "passes/frame_scene.h"

#include <cstdint>
#include <vector>

namespace obscura::passes {

// 32-bit float depth: cascades span a whole scene along the light and cube faces a perspective
// depth range, both beyond what 16 or 24 bits resolve without raising the bias.
constexpr VkFormat kShadowAtlasFormat = VK_FORMAT_D32_SFLOAT;

// The atlas kept from frame to frame: a view is rendered again only when what it shows changed
// (its light, its tile, or a caster in it: geometry, transform, cut-out material). A static scene
// renders no shadow map at all after its first frame.
struct ShadowAtlasHistory {
    gpu::PersistentImage atlas;
    std::vector<uint64_t> viewKeys;  // of each view as the atlas holds it
};

// Returns the atlas, written as a depth attachment; read it with Usage::SampledCompute. With a
// history, only views whose key changed are rendered (into the kept atlas); without one (reference
// sub-frames, whose lights move every sub-frame) every view is.
gpu::ImageHandle addShadowMapPass(gpu::FrameGraph& graph, const FrameScene& scene,
                                  ShadowAtlasHistory* history = nullptr);

// Under GPU occlusion culling (ShadowAtlas::gpuCulledDraws, passes/occlusion_cull.h) the shadow
// maps are two passes over the views planShadowMaps() chose: the early one draws the draws drawn
// as they are and the culled draws' early instances; after the atlas's depth pyramid and the late
// culling, the late one draws the culled draws' late instances into the same views.
struct ShadowMapRender {
    gpu::ImageHandle atlas;       // as the last pass left it
    std::vector<uint32_t> views;  // the views rendered this frame
    bool wholeAtlas = true;       // the atlas is cleared whole
    bool rendered = true;         // false: nothing changed, the kept atlas is read as it is
};
// The views to render this frame (the history takes their keys) and the atlas they go into.
ShadowMapRender planShadowMaps(gpu::FrameGraph& graph, const FrameScene& scene, ShadowAtlasHistory* history);
void addShadowMapEarlyPass(gpu::FrameGraph& graph, const FrameScene& scene, ShadowMapRender& render,
                           const CulledDraws& early);
gpu::ImageHandle addShadowMapLatePass(gpu::FrameGraph& graph, const FrameScene& scene, ShadowMapRender early,
                                      const CulledDraws& late);

}  // namespace obscura::passes
