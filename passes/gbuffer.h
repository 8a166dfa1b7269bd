// G-buffer pass (frame step 4): rasterises every draw into the thin G-buffer of seed 004.
#pragma once

#include "gpu/frame_graph.h"
#include "passes/frame_scene.h"
#include "passes/pipeline_cache.h"

#include <string>

namespace obscura::passes {

struct GBuffer {
    gpu::ImageHandle depth;             // D32_SFLOAT_S8_UINT (stencil bit 0x80 reserved for MSAA)
    gpu::ImageHandle normalRoughness;   // RGBA8 UNORM: best-fit normal + roughness
    gpu::ImageHandle albedoMetallic;    // RGBA8 sRGB: albedo + metallic
    gpu::ImageHandle instance;          // R32 UINT: instance index + 1 (low 24 bits, 0 where nothing drew),
                                        // the material's occlusion (top 8 bits): common/instance_target.glsl
    // RG16 SFLOAT, with motion blur only (FrameScene::motionBlur): the displacement in pixels from
    // the shutter's open to its close of what moving draws cover, kStaticVelocity elsewhere.
    gpu::ImageHandle velocity;
};

// The instance target keeps 24 bits for the instance index + 1.
constexpr uint32_t kMaxInstanceRecords = (1u << 24) - 1u;

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT_S8_UINT;
constexpr VkFormat kNormalRoughnessFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kAlbedoMetallicFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kInstanceFormat = VK_FORMAT_R32_UINT;
// Half floats, not the seed's R8G8 gamma-2 encoding: the 8 bits are off by up to half a pixel on
// the longest streaks (tests/unit/velocity_encoding_test.cpp measures both), cannot hold the
// static-pixel marker below, nor displacements beyond the blur's reach.
constexpr VkFormat kVelocityFormat = VK_FORMAT_R16G16_SFLOAT;
// The velocity target's clear value: the pixel moves with the camera (STATIC_VELOCITY in
// shaders/common/motion_velocity.glsl).
constexpr float kStaticVelocity = -65504.0f;

// The scene's vertex input (Vertex, the instance records; shaders/gbuffer.vert), shared by the
// passes that draw the scene's materials.
void setSceneVertexInput(gpu::GraphicsPipelineDesc& desc);

// Records one draw of the scene with its material textures pushed into set 1 (unless `pushed`
// holds them already) and `push` as push constants (its first uint: the draw's first instance).
void recordMaterialDraw(gpu::Device& device, VkCommandBuffer cmd, const gpu::Pipeline& pipeline,
                        const FrameScene& scene, const Draw& draw, const MaterialTextures*& pushed,
                        const void* push, uint32_t pushSize);

// The G-buffer's images at the scene's size, named "<prefix>.depth" etc. (a velocity target with
// motion blur).
GBuffer createGBufferImages(gpu::FrameGraph& graph, const FrameScene& scene, VkSampleCountFlagBits samples,
                            const std::string& prefix);

// Draws every opaque draw of the scene (Draw::transparent ones are the transparent pass's). With
// more than one sample (render setting msaa) every target is multisampled; the custom resolve
// (msaa_resolve.h) turns it into the single-sample G-buffer the other passes read.
// Cut-out materials (opacityThreshold) cover the samples their opacity passes at each sample's
// position (alpha-test supersampling), or with `alphaToCoverage` the fraction of the samples their
// opacity gives (seed 000 "Deferred MSAA \ alpha test SSAA", "performance shortcuts (3)").
GBuffer addGBufferPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                       const gpu::ImagePtr& bestFitNormals, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT,
                       bool alphaToCoverage = false);

}  // namespace obscura::passes
