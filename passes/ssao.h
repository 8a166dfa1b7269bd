// Screen-space ambient occlusion (seed 004 "SSAO improvements"), two passes: volumetric obscurance
// (Loos & Sloan 2010) with 4 samples per pixel at half resolution, taking its half-resolution
// geometry from the G-buffer itself; then the accumulation over frames with reprojection and the
// bilateral blur that smooths it keeping depth edges, in one pass. The lighting pass upsamples the
// result with sampleAmbientAccess() (shaders/common/ssao_upsample.glsl).
#pragma once

#include "gpu/history_images.h"
#include "passes/frame_resources.h"
#include "passes/frame_scene.h"

namespace obscura::passes {

// Accumulated accessibility (x) and the frames it holds / kSsaoHistoryFrames (y).
constexpr VkFormat kSsaoHistoryFormat = VK_FORMAT_R16G16_SFLOAT;
constexpr uint32_t kSsaoHistoryFrames = 8;

struct SsaoSettings {
    float radius = 0.5f;     // of the sampling sphere, in scene units
    float intensity = 1.0f;  // scales the occlusion: accessibility = 1 - intensity * occlusion
};

// The temporal accumulation's history (an explicit history input, STYLE.md): persistent
// ping-pong images; the caller keeps it across frames, says whether last frame's images are usable
// (same size, projection and settings) and how this frame's view space maps to last frame's.
struct SsaoHistory {
    gpu::HistoryImages accessibility;  // kSsaoHistoryFormat
    gpu::HistoryImages depth;          // kSsaoDepthFormat
    bool valid = false;      // set by the caller: last frame's images may be reprojected
    Mat4 viewToPreviousView{};  // set by the caller (column-major, as the shader reads it)
    uint64_t frame = 0;      // turns the sample pattern
};

SsaoResult addSsaoPasses(gpu::FrameGraph& graph, const FrameScene& scene,
                         const GBuffer& gbuffer, const SsaoSettings& settings, SsaoHistory& history);

}  // namespace obscura::passes
