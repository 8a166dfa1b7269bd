// The frame's resources as one pass hands them to the next (frame-graph handles, their formats
// and layout): the G-buffer, SSAO's result, a textured dome's lighting. Passes share these
// descriptions, never each other's headers.
#pragma once

#include "gpu/frame_graph.h"
#include "passes/frame_scene.h"

#include <string>

namespace obscura::passes {

// --- The G-buffer (passes/gbuffer.h writes it, seed 004's thin layout) --------------------------

struct GBuffer {
    gpu::ImageHandle depth;             // gbufferDepthFormat(): D32_SFLOAT_S8_UINT (stencil bit 0x80
                                        // reserved for MSAA), multisampled D32_SFLOAT; resolved
                                        // from MSAA, R32_SFLOAT unless `stencil` is invalid
    gpu::ImageHandle normalRoughness;   // RGBA8 UNORM: best-fit normal + roughness
    gpu::ImageHandle albedoMetallic;    // RGBA8 sRGB: albedo + metallic
    gpu::ImageHandle instance;          // R32 UINT: instance index + 1 (low 24 bits, 0 where nothing drew),
                                        // the material's occlusion (top 8 bits): common/instance_target.glsl
    // RG16 SFLOAT, with motion blur only (FrameScene::motionBlur): the displacement in pixels from
    // the shutter's open to its close of what moving draws cover, kStaticVelocity elsewhere.
    gpu::ImageHandle velocity;
    // The stencil bits the lighting reads, where `depth` has no stencil aspect: R8 UINT (the MSAA
    // resolve's edge bit, in a frame without clip volumes). Invalid: `depth`'s stencil.
    gpu::ImageHandle stencil;
    // kEmissionFormat, where a drawn material's emissiveColor reads a texture (hasEmissionTarget):
    // that emission, pre-exposed (CameraData::exposureScale), 0 where other draws cover. The
    // lighting pass adds it for the materials whose emission is textured; the multisampled
    // G-buffer's is read per sample and not resolved.
    gpu::ImageHandle emission;
};

// The instance target keeps 24 bits for the instance index + 1.
constexpr uint32_t kMaxInstanceRecords = (1u << 24) - 1u;

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT_S8_UINT;
// A multisampled G-buffer's depth keeps no stencil: its samples' depths are all the resolve and the
// per-sample lighting read, and the stencil's bits (clip volumes, the per-sample mask) live in the
// single-sample G-buffer the resolve writes. A stencil aspect would double the target (depth with
// stencil takes 8 bytes a sample): 31.6 MiB at 1080p with 4 samples.
constexpr VkFormat kMultisampledDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkFormat gbufferDepthFormat(VkSampleCountFlagBits samples) {
    return samples == VK_SAMPLE_COUNT_1_BIT ? kDepthFormat : kMultisampledDepthFormat;
}
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

// Half floats: the pre-exposed emission of a texture is near the light the frame is exposed for.
constexpr VkFormat kEmissionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

// Whether the G-buffer has an emission target: some drawn surface's material has textured
// emission (kMaterialTexturedEmission). It is RT4; a frame without a velocity target leaves RT3
// unbound.
bool hasEmissionTarget(const FrameScene& scene);

// Imports the scene's records into `graph` (FrameScene::buffers).
void importSceneBuffers(gpu::FrameGraph& graph, FrameScene& scene);

// The G-buffer's images at the scene's size, named "<prefix>.depth" etc. (a velocity target with
// motion blur, and an emission target with textured emission).
GBuffer createGBufferImages(gpu::FrameGraph& graph, const FrameScene& scene, VkSampleCountFlagBits samples,
                            const std::string& prefix);

// --- Ambient occlusion (passes/ssao.h) ----------------------------------------------------------

// Linear view depth (distance along the view axis) at half resolution. Seed 004 packs depth into
// two 8-bit channels beside the AO so that the blur fetches both at once; a [0, 1] fixed-point
// encoding over USD's default clipping range (1 to 1e6) is far too coarse for depths compared to a
// fraction of the sampling radius, so depth keeps 32-bit float and the blur fetches twice.
constexpr VkFormat kSsaoDepthFormat = VK_FORMAT_R32_SFLOAT;
// Ambient accessibility, 1 = unoccluded.
constexpr VkFormat kSsaoAccessibilityFormat = VK_FORMAT_R8_UNORM;

// Both images are ceil(width / 2) x ceil(height / 2): half-resolution texel (x, y) covers
// full-resolution pixels (2x..2x+1, 2y..2y+1).
struct SsaoResult {
    // The accumulated accessibility, blurred (ssao.h), kSsaoAccessibilityFormat.
    gpu::ImageHandle accessibility;
    gpu::ImageHandle halfDepth;      // kSsaoDepthFormat, the depths the accessibility belongs to
};

// --- A textured dome's lighting (passes/environment_prefilter.h) ---------------------------------

// Level i holds GGX perceptual roughness i / (kPrefilteredLevels - 1); level 0, the mirror, is
// kPrefilteredWidth x kPrefilteredWidth / 2 (latlong), the last 16 x 8.
constexpr VkFormat kPrefilteredFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr uint32_t kPrefilteredWidth = 512;
constexpr uint32_t kPrefilteredLevels = 6;
// vec4 per coefficient (rgb A_l L_lm, a unused), std430.
constexpr uint32_t kIrradianceCoefficients = 9;
constexpr VkDeviceSize kIrradianceBufferSize = kIrradianceCoefficients * 4 * sizeof(float);

struct EnvironmentLighting {
    gpu::ImageHandle prefiltered;  // kPrefilteredFormat, kPrefilteredLevels mips, storage + sampled
    gpu::BufferHandle irradiance;  // kIrradianceBufferSize bytes, storage
    VkSampler sampler = VK_NULL_HANDLE;  // trilinear, repeating in longitude, clamped in latitude
};

}  // namespace obscura::passes
