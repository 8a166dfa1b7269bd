// What a surface point receives from the frame's lights, shared by the deferred lighting pass
// (lighting.comp, G-buffer surfaces) and the forward pass of transparent surfaces
// (transparent.frag): the textured dome's sample and each light's reflection with its shadow.
//
// The includer declares, before including this file (frame_data.glsl types):
//   EnvironmentData environment          the textured dome's frame (a uniform block)
//   vec4 irradianceSh[SH_COEFFICIENTS]   its irradiance coefficients (a storage buffer)
//   sampler2D prefilteredEnvironment     its prefiltered latlong chain (a 1x1 black image without one)
//   ShadowViewData shadowViews[], sampler2D shadowAtlas   (shadow_sampling.glsl)
//   the light buffer                     LIGHTS_BLOCK (frame_data.glsl)
#ifndef OBSCURA_SCENE_LIGHTING_GLSL
#define OBSCURA_SCENE_LIGHTING_GLSL

#include "light_evaluation.glsl"
#include "environment_map.glsl"
#include "shadow_sampling.glsl"

// The textured dome seen from s: SH irradiance around N, the prefiltered chain along the mirror
// direction at the lobes' roughness (the split sum's N = V = R lookup), in the dome's frame.
EnvironmentSample sampleEnvironment(SurfacePoint s) {
    if (!hasLightKind(LIGHT_KINDS, LIGHT_KIND_TEXTURED_DOME) || environment.params.x < 0.5)
        return EnvironmentSample(vec3(1.0), vec3(1.0), vec3(1.0));
    mat3 toDome = mat3(environment.worldToDome);
    vec3 N = normalize(toDome * s.N);
    vec3 R = normalize(toDome * reflect(-s.V, s.N));
    vec2 uv = latlongUv(R);
    float lastLevel = float(textureQueryLevels(prefilteredEnvironment) - 1);
    EnvironmentSample e;
    e.diffuse = shIrradiance(irradianceSh, N) / PI;
    e.specular = textureLod(prefilteredEnvironment, uv, prefilteredLod(s.roughness, lastLevel)).rgb;
    e.coat = s.clearcoat > 0.0
        ? textureLod(prefilteredEnvironment, uv, prefilteredLod(s.clearcoatRoughness, lastLevel)).rgb
        : vec3(0.0);
    return e;
}

// One light's reflection off s towards the eye, scaled by its shadow maps' visibility; the
// shadow lookups only where the light reaches the surface at all. `kinds`: the kinds of light the
// caller may pass (light_evaluation.glsl hasLightType); without a shadow projection among them the
// lookups are left out of the pipeline: lavapipe pays for their code in every light's loop body
// even where none runs (bench/RESULTS.md).
vec3 reflectShadowedLight(SurfacePoint s, LightData light, float viewDistance, uint kinds) {
    vec3 reflected = reflectFromLight(s, light, kinds);
    if (light.shadow.y > 0u && any(greaterThan(reflected, vec3(0.0))))
        reflected *= shadowVisibility(light, s.P, s.N, viewDistance, s.shadowTurn, kinds);
    return reflected;
}

// `light`'s reflection off s (of the kinds `kinds`) where its clip volume, if it has one, holds the
// surface: a clipped light reaches only surfaces inside its volume (seed 004 "clip volumes").
// `insideClipVolumes`: the volumes' stencil bits the surface lies in (~0u: every volume).
vec3 clippedLight(SurfacePoint s, LightData light, float viewDistance, uint insideClipVolumes, uint kinds) {
    if (light.shadow.w != 0u && (insideClipVolumes & light.shadow.w) == 0u) return vec3(0.0);
    return reflectShadowedLight(s, light, viewDistance, kinds);
}

// The reflection of the lights that reach every surface, the distant lights and the domes (the
// light buffer's first), a loop for each compiled for its own kinds alone (hasLightType); the
// local lights follow them in the buffer.
vec3 reflectDistantLightsAndDomes(SurfacePoint s, float viewDistance, uint insideClipVolumes) {
    vec3 radiance = vec3(0.0);
    for (uint i = 0u; i < distantLightCount; ++i)
        radiance += clippedLight(s, lights[i], viewDistance, insideClipVolumes, LIGHT_KINDS & DISTANT_LIGHT_KINDS);
    for (uint i = distantLightCount; i < distantLightCount + domeLightCount; ++i)
        radiance += clippedLight(s, lights[i], viewDistance, insideClipVolumes, LIGHT_KINDS & DOME_LIGHT_KINDS);
    return radiance;
}

#endif
