// A textured DomeLight's lighting, made once per texture (not per frame): the prefiltered
// specular chain (split sum, Karis 2013) and the irradiance as 9 spherical-harmonic coefficients
// (Ramamoorthi & Hanrahan 2001), both in the dome's own frame so that rotating the dome costs
// nothing. The lighting pass samples them (shaders/common/environment_map.glsl).
#pragma once

#include "gpu/frame_graph.h"
#include "passes/pipeline_cache.h"

namespace obscura::passes {

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

// The pass that writes `prefiltered` (its name in the frame graph and in pass timings).
constexpr const char* kEnvironmentPrefilterPass = "environment_prefilter";

// Writes both from `source`, a latlong radiance texture with its full mip chain, read through
// target.sampler. Two compute passes: environment_prefilter (one dispatch per level) and
// environment_irradiance.
void addEnvironmentPrefilterPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, gpu::ImageHandle source,
                                   const EnvironmentLighting& target);

}  // namespace obscura::passes
