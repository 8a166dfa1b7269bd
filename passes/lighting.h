// Deferred lighting (frame step 7, pixel frequency and, with MSAA, sample frequency): a compute
// pass over the G-buffer that writes the light accumulation buffer.
#pragma once

#include "passes/frame_resources.h"

namespace obscura::passes {

// Seed 004 "HDR": the light accumulation fits 32 bits per pixel in B10G11R11_UFLOAT; RGBA16F is
// the higher-precision alternative (render setting lighting:halfFloat).
enum class LightAccumulation { SmallFloat, HalfFloat };

// Deferred MSAA (seed 000): with a multisampled G-buffer, pixels whose stencil carries the edge bit
// (msaa_resolve.h) are lit once per sample and resolved HDR-correctly; the pass counts them into
// `taggedPixelCount` (one uint, zeroed by the caller) for the render stats.
struct PerSampleLighting {
    GBuffer multisampled;
    gpu::BufferHandle taggedPixelCount;
};

// `ambient` is the SSAO result (ssao.h), applied to environment (dome) light only, as seed 004
// asks of ambient occlusion. `shadowAtlas` is the shadow-map pass's atlas (shadow_maps.h),
// filtered per pixel for each light with shadow views (FrameScene::shadows). `environment` holds
// the textured dome's prefiltered maps (environment_prefilter.h; placeholders when the scene has
// none).
gpu::ImageHandle addLightingPass(gpu::FrameGraph& graph, const FrameScene& scene,
                                 const GBuffer& gbuffer, const SsaoResult& ambient, gpu::ImageHandle shadowAtlas,
                                 const EnvironmentLighting& environment,
                                 LightAccumulation accumulation = LightAccumulation::SmallFloat,
                                 const PerSampleLighting* perSample = nullptr);

}  // namespace obscura::passes
