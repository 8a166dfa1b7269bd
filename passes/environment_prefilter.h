// A textured DomeLight's lighting, made once per texture (not per frame): the prefiltered
// specular chain (split sum, Karis 2013) and the irradiance as 9 spherical-harmonic coefficients
// (Ramamoorthi & Hanrahan 2001), both in the dome's own frame so that rotating the dome costs
// nothing. The lighting pass samples them (shaders/common/environment_map.glsl).
#pragma once

#include "gpu/frame_graph.h"
#include "passes/frame_resources.h"

namespace obscura::passes {

// The pass that writes `prefiltered` (its name in the frame graph and in pass timings).
constexpr const char* kEnvironmentPrefilterPass = "environment_prefilter";

// Writes both from `source`, a latlong radiance texture with its full mip chain, read through
// target.sampler. Two compute passes: environment_prefilter (one dispatch per level) and
// environment_irradiance.
// Returns `target` as the passes leave it.
EnvironmentLighting addEnvironmentPrefilterPasses(gpu::FrameGraph& graph, gpu::ImageHandle source,
                                                  const EnvironmentLighting& target);

}  // namespace obscura::passes
