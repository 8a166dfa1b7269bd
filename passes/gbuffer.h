// G-buffer pass (frame step 4): rasterises every draw into the thin G-buffer of seed 004.
#pragma once

#include "gpu/frame_graph.h"
#include "passes/frame_scene.h"
#include "passes/pipeline_cache.h"

namespace obscura::passes {

struct GBuffer {
    gpu::ImageHandle depth;             // D32_SFLOAT_S8_UINT (stencil bit 0x80 reserved for MSAA)
    gpu::ImageHandle normalRoughness;   // RGBA8 UNORM: best-fit normal + roughness
    gpu::ImageHandle albedoMetallic;    // RGBA8 sRGB: albedo + metallic
    gpu::ImageHandle instance;          // R32 UINT: instance index + 1, 0 where nothing drew
};

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT_S8_UINT;
constexpr VkFormat kNormalRoughnessFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kAlbedoMetallicFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kInstanceFormat = VK_FORMAT_R32_UINT;

// The G-buffer's images at the scene's size, named "<prefix>.depth" etc.
GBuffer createGBufferImages(gpu::FrameGraph& graph, const FrameScene& scene, VkSampleCountFlagBits samples,
                            const std::string& prefix);

// With more than one sample (render setting msaa) every target is multisampled; the custom
// resolve (msaa_resolve.h) turns it into the single-sample G-buffer the other passes read.
GBuffer addGBufferPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                       const gpu::ImagePtr& bestFitNormals, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

}  // namespace obscura::passes
