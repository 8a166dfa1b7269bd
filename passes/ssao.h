// Screen-space ambient occlusion (seed 004 "SSAO improvements"): volumetric obscurance (Loos &
// Sloan 2010) with 4 samples per pixel at half resolution, accumulated over frames with
// reprojection, then a bilateral blur that keeps depth edges. The lighting pass upsamples the result with sampleAmbientAccess()
// (shaders/common/ssao_upsample.glsl).
#pragma once

#include "passes/gbuffer.h"

namespace obscura::passes {

// Linear view depth (distance along the view axis) at half resolution. Seed 004 packs depth into
// two 8-bit channels beside the AO so that the blur fetches both at once; a [0, 1] fixed-point
// encoding over USD's default clipping range (1 to 1e6) is far too coarse for depths compared to a
// fraction of the sampling radius, so depth keeps 32-bit float and the blur fetches twice.
constexpr VkFormat kSsaoDepthFormat = VK_FORMAT_R32_SFLOAT;
// Ambient accessibility, 1 = unoccluded.
constexpr VkFormat kSsaoAccessibilityFormat = VK_FORMAT_R8_UNORM;

// Accumulated accessibility (x) and the frames it holds / kSsaoHistoryFrames (y).
constexpr VkFormat kSsaoHistoryFormat = VK_FORMAT_R16G16_SFLOAT;
constexpr uint32_t kSsaoHistoryFrames = 8;

struct SsaoSettings {
    float radius = 0.5f;     // of the sampling sphere, in scene units
    float intensity = 1.0f;  // scales the occlusion: accessibility = 1 - intensity * occlusion
};

// The temporal accumulation's history (an explicit history input, STYLE.md): two pairs of
// persistent images, one read as last frame's and one written; the caller keeps it across frames,
// says whether last frame's pair is usable (same size, projection and settings) and how this
// frame's view space maps to last frame's.
struct SsaoHistory {
    std::array<gpu::ImagePtr, 2> accessibility;  // kSsaoHistoryFormat
    std::array<gpu::ImagePtr, 2> depth;          // kSsaoDepthFormat
    std::array<VkImageLayout, 2> accessibilityLayout{VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED};
    std::array<VkImageLayout, 2> depthLayout{VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED};
    uint32_t written = 0;    // the pair the last frame wrote
    bool valid = false;      // set by the caller: last frame's pair may be reprojected
    Mat4 viewToPreviousView{};  // set by the caller (column-major, as the shader reads it)
    uint64_t frame = 0;      // turns the sample pattern
};

// Both images are ceil(width / 2) x ceil(height / 2): half-resolution texel (x, y) covers
// full-resolution pixels (2x..2x+1, 2y..2y+1).
struct SsaoResult {
    gpu::ImageHandle accessibility;  // kSsaoAccessibilityFormat
    gpu::ImageHandle halfDepth;      // kSsaoDepthFormat, the depths the accessibility belongs to
    // The history images as imported this frame, [pair index], for keepSsaoHistory.
    std::array<gpu::ImageHandle, 2> historyAccessibility;
    std::array<gpu::ImageHandle, 2> historyDepth;
};

SsaoResult addSsaoPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                         const GBuffer& gbuffer, const SsaoSettings& settings, SsaoHistory& history);

// After the graph is compiled: records the layouts this frame leaves both history pairs in.
void keepSsaoHistory(const gpu::FrameGraph& graph, const SsaoResult& result, SsaoHistory& history);

}  // namespace obscura::passes
