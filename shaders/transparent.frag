#version 460
#extension GL_GOOGLE_include_directive : require
// Transparent surfaces (frame step 8), forward: after deferred lighting, into the pre-exposed light
// accumulation, without MSAA (seed 000 "MSAA \ performance shortcuts (3)": render only opaque with
// MSAA, then transparents without). Every light, its shadows and the dome light the surface through
// the code the lighting pass uses (common/scene_lighting.glsl); no tiles, each local light within
// its influence range.
//
// UsdPreviewSurface opacity (https://openusd.org/release/spec_usdpreviewsurface.html): "even a
// fully transparent object still receives lighting as, for example, perfectly clear glass still has
// a specular response". So opacity is the coverage of the diffuse layer (and its emission): the
// output is premultiplied, diffuse x opacity + specular, alpha = opacity, blended
// src + dst (1 - alpha): a matte surface blends as lit * opacity + behind * (1 - opacity), and
// glass keeps its reflections. Built with SPHERE_IMPOSTOR for sphere impostors
// (common/sphere_impostor.glsl): the near side of the sphere each cube bounds.
#include "common/frame_data.glsl"
CAMERA_BLOCK(0);
#define MATERIAL_LOD_BIAS camera.textureLodBias
#include "common/material_inputs.glsl"
#include "common/light_evaluation.glsl"
#include "common/environment_map.glsl"
#include "common/view_depth.glsl"
#include "common/sphere_impostor.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inColor;  // displayColor, displayOpacity
layout(location = 2) in vec3 inWorldPosition;
layout(location = 3) flat in uint inInstance;
layout(location = 4) in vec2 inUv;
layout(location = 5) in vec4 inTangent;

layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Materials { MaterialData materials[]; };
LIGHTS_BLOCK(3);
// The depth transparents are tested against and fade with: the G-buffer's (its max over the
// samples where the G-buffer is multisampled: seed 000 "Deferred MSAA \ performance shortcuts (2)").
layout(set = 0, binding = 4) uniform sampler2D sceneDepth;
layout(set = 0, binding = 5, std430) readonly buffer ShadowViews { ShadowViewData shadowViews[]; };
layout(set = 0, binding = 6) uniform sampler2D shadowAtlas;
ENVIRONMENT_BLOCK(7);
layout(set = 0, binding = 8, std430) readonly buffer EnvironmentIrradiance { vec4 irradianceSh[SH_COEFFICIENTS]; };
layout(set = 0, binding = 9) uniform sampler2D prefilteredEnvironment;
// The draw's material textures, pushed per draw as in the G-buffer pass.
layout(set = 1, binding = 0) uniform sampler2D diffuseTexture;
layout(set = 1, binding = 1) uniform sampler2D roughnessTexture;
layout(set = 1, binding = 2) uniform sampler2D metallicTexture;
layout(set = 1, binding = 3) uniform sampler2D opacityTexture;
layout(set = 1, binding = 4) uniform sampler2D normalTexture;
layout(set = 1, binding = 5) uniform sampler2D occlusionTexture;
layout(set = 1, binding = 6) uniform sampler2D emissiveTexture;

layout(push_constant) uniform Push {
    uint instanceIndex;    // read by the vertex stage (gbuffer.vert)
    float fadeDistance;    // render setting transparents:fadeDistance, scene units; 0: no fade
} push;

#include "common/scene_lighting.glsl"
#include "common/anisotropic_lobe.glsl"

layout(location = 0) out vec4 outRadiance;  // premultiplied, pre-exposed
layout(location = 1) out vec4 outCoverage;  // x and w: opacity (alpha "over" alpha)

// Soft-particle depth fade: the surface fades out over `fadeDistance` in front of the opaque
// surface behind it, so a pane meeting a floor shows no hard seam. `depthImage` holds the opaque
// depth per pixel: the G-buffer's here; a multisampled G-buffer supplies the max of its samples
// (seed 000 "Deferred MSAA \ performance shortcuts (2)": max depth works and is N times faster
// than per-sample passes). Returns 0 where the opaque surface is in front (the depth test).
float depthFade(sampler2D depthImage, ivec2 pixel, float fragmentDepth, float fadeDistance) {
    float opaqueDepth = texelFetch(depthImage, pixel, 0).r;
    if (fragmentDepth >= opaqueDepth) return 0.0;
    if (fadeDistance <= 0.0) return 1.0;
    float gap = linearDepthFromDevice(camera.projection, opaqueDepth) -
                linearDepthFromDevice(camera.projection, fragmentDepth);
    return clamp(gap / fadeDistance, 0.0, 1.0);
}

void main() {
    InstanceData inst = instances[inInstance];
    MaterialData mat = materials[inst.materialIndex];
#ifdef SPHERE_IMPOSTOR
    ImpostorHit sphere = impostorHit(camera.viewProjection, inst.normalMatrix, inWorldPosition, inTangent);
    if (!sphere.hit) discard;
    vec3 worldPosition = sphere.position;
    float fragmentDepth = sphere.depth;
    vec4 tangent = impostorTangent(inst.model, sphere.normal);
    vec3 n = sphere.normal;
    bool backFacing = sphere.backFacing;
#else
    vec3 worldPosition = inWorldPosition;
    float fragmentDepth = gl_FragCoord.z;
    vec4 tangent = inTangent;
    vec3 n = normalize(inNormal);
    bool backFacing = !gl_FrontFacing;
#endif
    if ((inst.flags & INSTANCE_DOUBLE_SIDED) != 0u && backFacing) n = -n;
    n = perturbedNormal(n, tangent, mat.textures[TEXTURE_NORMAL], normalTexture, inUv);
    vec3 albedo = albedoFromDisplayColor(inst)
                      ? displayAlbedo(inst, inColor, mat.diffuseRoughness.rgb)
                      : colorInput(mat.diffuseRoughness.rgb, mat.textures[TEXTURE_DIFFUSE], diffuseTexture, inUv);
    float roughness = scalarInput(mat.diffuseRoughness.a, mat.textures[TEXTURE_ROUGHNESS], roughnessTexture, inUv);
    float metallic = scalarInput(mat.emissiveMetallic.a, mat.textures[TEXTURE_METALLIC], metallicTexture, inUv);
    float opacity = scalarInput(mat.opacity.x, mat.textures[TEXTURE_OPACITY], opacityTexture, inUv);
    // Hydra's fallback material: displayOpacity varying over the prim (the constant one is the
    // material record's), or the instance's own, which replaces both; a material whose opacity
    // reads a primvar (its record's opacity then 1) takes the vertex's or the instance's.
    if ((inst.flags & INSTANCE_DISPLAY_OPACITY) != 0u) opacity = displayColorOf(inst, inColor).a;
    else if ((inst.flags & (INSTANCE_VERTEX_COLOR | INSTANCE_VERTEX_OPACITY)) != 0u) opacity *= inColor.a;
    float occlusion = scalarInput(mat.opacity.z, mat.textures[TEXTURE_OCCLUSION], occlusionTexture, inUv);
    // The same principal lobe as opaque surfaces (the G-buffer pass), so a material looks alike
    // at any opacity.
    if (mat.anisotropy.x > 0.0)
        principalLobe(n, roughness, tangent, mat.anisotropy.xy, worldPosition,
                      normalize(camera.position.xyz - worldPosition));

    float fade = depthFade(sceneDepth, ivec2(gl_FragCoord.xy), fragmentDepth, push.fadeDistance);
    if (fade <= 0.0) discard;

    SurfacePoint s = surfaceFromMaterial(mat, albedo, metallic);
    s.P = worldPosition;
    s.N = n;
    s.V = normalize(camera.position.xyz - s.P);
    s.roughness = roughness;
    // No SSAO: its obscurance is the opaque surface's behind; the material's occlusion still holds.
    s.ambientAccess = occlusion;
    s.environment = sampleEnvironment(s);
    s.shadowTurn = shadowFilterTurn(floor(gl_FragCoord.xy), camera.noiseFrame);
    // Coverage scales the diffuse layer only (see above): the lights' response is linear in it.
    s.diffuse *= opacity;
    float viewDistance = linearDepthFromDevice(camera.projection, fragmentDepth);
    // Clipped lights light transparents unclipped (~0u: inside every volume): their volumes mark
    // opaque pixels in stencil.
    vec3 emission = colorInput(mat.emissiveMetallic.rgb, mat.textures[TEXTURE_EMISSIVE], emissiveTexture, inUv);
    vec3 radiance = emission * opacity + reflectDistantLightsAndDomes(s, viewDistance, ~0u);
    for (uint i = distantLightCount + domeLightCount; i < lightCount; ++i)
        if (lightReaches(lights[i], s.P))
            radiance += reflectShadowedLight(s, lights[i], viewDistance, LIGHT_KINDS & LOCAL_LIGHT_KINDS);
    // The fade thins the whole surface, reflections included, as coverage.
    outRadiance = vec4(radiance * camera.exposureScale * fade, opacity * fade);
    outCoverage = vec4(opacity * fade, 0.0, 0.0, opacity * fade);
}
