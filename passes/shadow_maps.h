// Shadow maps (frame step 3, before the G-buffer): depth-only rendering of the scene's draws into
// every view of the frame's shadow atlas (FrameScene::shadows), one tile per view. The lighting
// pass filters the atlas per pixel (shaders/common/shadow_sampling.glsl).
#pragma once

#include "gpu/frame_graph.h"
#include "passes/frame_scene.h"
#include "passes/pipeline_cache.h"

namespace obscura::passes {

// 32-bit float depth: cascades span a whole scene along the light and cube faces a perspective
// depth range, both beyond what 16 or 24 bits resolve without raising the bias.
constexpr VkFormat kShadowAtlasFormat = VK_FORMAT_D32_SFLOAT;

// Returns the atlas, written as a depth attachment; read it with Usage::SampledCompute.
gpu::ImageHandle addShadowMapPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene);

}  // namespace obscura::passes
