// G-buffer pass, fragment stage shared by the static and the moving draws: the thin G-buffer of
// seed 004 ("G-Buffer layout"):
//   RT0 RGBA8  best-fit normal (24 bits) + roughness (8 bits)
//   RT1 RGBA8 sRGB  albedo + metallic
//   RT2 R32UI  instance index + 1 (0: nothing drawn) for per-prim data and the primId AOV, and the
//              material's occlusion in its top 8 bits (instance_target.glsl)
// (and, with motion blur, RT3 RG16F velocity, written by moving draws only: gbuffer_moving.frag;
// with textured emission, RT4 RGBA16F emission, pre-exposed, written by the draws whose materials'
// emission is textured: passes/frame_resources.h GBuffer::emission).
#ifndef OBSCURA_GBUFFER_SURFACE_GLSL
#define OBSCURA_GBUFFER_SURFACE_GLSL

#ifdef SPHERE_IMPOSTOR
// The sphere lies behind the cube face that answers for the pixel (sphere_impostor.glsl), so the
// written depth is never nearer than the face's: the depth test may still reject fragments before
// shading. (Not so where the eye is inside the cube or the sphere, whose far side answers there.)
layout(depth_greater) out float gl_FragDepth;
#endif

#include "frame_data.glsl"
CAMERA_BLOCK(0);
#define MATERIAL_LOD_BIAS camera.textureLodBias
#include "best_fit_normals.glsl"
#include "material_inputs.glsl"
#include "instance_target.glsl"
#include "msaa_samples.glsl"
#include "sphere_impostor.glsl"

// Built twice (cmake variants): with OPAQUE_SURFACE for draws whose material cuts nothing out
// (passes/gbuffer.cpp picks by Draw::opacityCutout). Those never discard nor narrow the sample
// mask, so their depth test can run before the shader: a fragment behind what is already drawn
// costs no shading, which a shader that may discard forbids.
#ifdef OPAQUE_SURFACE
layout(early_fragment_tests) in;
#endif

// Built with PER_SAMPLE_SHADING for frames whose MSAA samples resolve over the pixel's box (a
// still's, the reference's: SampleResolve::PixelBox, passes/gbuffer.cpp): one invocation per sample, its inputs interpolated
// at the sample, so that each sample's surface is looked up where the sample lies. Shaded once at
// the pixel's centre for all of them, a texture is seen only where the frames' jitter puts that
// centre, a quarter of the pixel's width with 4 samples, and the mean never covers the pixel.
#ifdef PER_SAMPLE_SHADING
#define SURFACE_INPUT sample in
#else
#define SURFACE_INPUT in
#endif
layout(location = 0) SURFACE_INPUT vec3 inNormal;
layout(location = 1) SURFACE_INPUT vec4 inColor;
layout(location = 2) SURFACE_INPUT vec3 inWorldPosition;
layout(location = 3) flat in uint inInstance;
layout(location = 4) SURFACE_INPUT vec2 inUv;
layout(location = 5) SURFACE_INPUT vec4 inTangent;

layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Materials { MaterialData materials[]; };
layout(set = 0, binding = 3) uniform sampler2D fittingScale;
// The frame's lights, for the principal lobe of anisotropic materials (anisotropic_lobe.glsl).
LIGHTS_BLOCK(4);
#include "anisotropic_lobe.glsl"
// The draw's material textures, pushed per draw (white where an input is constant).
layout(set = 1, binding = 0) uniform sampler2D diffuseTexture;
layout(set = 1, binding = 1) uniform sampler2D roughnessTexture;
layout(set = 1, binding = 2) uniform sampler2D metallicTexture;
layout(set = 1, binding = 3) uniform sampler2D opacityTexture;
layout(set = 1, binding = 4) uniform sampler2D normalTexture;
layout(set = 1, binding = 5) uniform sampler2D occlusionTexture;
layout(set = 1, binding = 6) uniform sampler2D emissiveTexture;

// Mirrors GBufferPush in passes/gbuffer.cpp (the vertex stage reads the first member).
layout(push_constant) uniform Push {
    uint instanceIndex;
    uint sampleCount;       // the G-buffer's samples per pixel (render setting msaa)
    uint alphaToCoverage;   // render setting msaa:alphaToCoverage
} push;

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outAlbedoMetallic;
layout(location = 2) out uint outInstance;
// Attached where the frame has an emission target; pipelines whose materials' emission is constant
// leave it untouched (passes/gbuffer.cpp).
layout(location = 4) out vec4 outEmission;

// The samples a cut-out material (opacityThreshold) covers. Seed 000 "Deferred MSAA \ alpha test
// SSAA": the rasteriser's coverage only knows triangle edges, so each sample's opacity is read at
// the texture coordinates moved by the sample's offset from the pixel centre through the UV
// derivatives, and the sample is kept where it passes the threshold. With alpha-to-coverage
// instead (seed "performance shortcuts (3)"), the pixel's opacity, sharpened around the threshold
// over its screen-space gradient, keeps that fraction of the samples: one lookup. (The hardware's
// alpha-to-coverage reads RT0's alpha, which holds roughness, so the mask is made here.)
uint cutoutCoverage(MaterialData mat, vec2 uv) {
    float threshold = mat.opacity.y;
#ifdef PER_SAMPLE_SHADING
    const int samples = 1;  // the invocation's own sample, at `uv`: the mask's other bits do not count
#else
    int samples = int(push.sampleCount);
#endif
    if (threshold <= 0.0) return ~0u;
    if (samples <= 1) return opacityAt(mat, opacityTexture, uv) < threshold ? 0u : ~0u;
    if (push.alphaToCoverage != 0u) {
        float alpha = opacityAt(mat, opacityTexture, uv);
        float covered = clamp((alpha - threshold) / max(fwidth(alpha), 1e-4) + 0.5, 0.0, 1.0);
        uint kept = uint(round(covered * float(samples)));
        return kept >= 32u ? ~0u : (1u << kept) - 1u;
    }
    vec2 dx = dFdx(uv), dy = dFdy(uv);
    uint mask = 0u;
    for (int s = 0; s < samples; ++s) {
        vec2 offset = standardSampleLocation(samples, s) - 0.5;
        if (opacityAt(mat, opacityTexture, uv + offset.x * dx + offset.y * dy) >= threshold) mask |= 1u << uint(s);
    }
    return mask;
}

#ifdef SPHERE_IMPOSTOR
// How far the fragment's point moves along the cube's face to sample s of an N-sample pixel at the
// standard sample locations (msaa_samples.glsl), from its screen derivatives `dx`, `dy` (taken
// where every invocation of the quad runs).
vec3 sampleShift(int samples, int s, vec3 dx, vec3 dy) {
    vec2 offset = standardSampleLocation(samples, s) - 0.5;
    return offset.x * dx + offset.y * dy;
}

// The sphere seen through sample s: the fragment's point and its offset from the centre, moved.
ImpostorHit sampleImpostorHit(InstanceData inst, int s, vec3 dx, vec3 dy) {
    vec3 shift = sampleShift(int(push.sampleCount), s, dx, dy);
    return impostorHit(camera.viewProjection, inst.normalMatrix, inWorldPosition + shift,
                       vec4(inTangent.xyz + shift, inTangent.w));
}

// The samples of the pixel whose lines of sight meet the sphere.
uint impostorCoverage(InstanceData inst, vec3 dx, vec3 dy) {
    uint mask = 0u;
    for (int s = 0; s < int(push.sampleCount); ++s)
        if (sampleImpostorHit(inst, s, dx, dy).hit) mask |= 1u << uint(s);
    return mask;
}
#endif

// Writes RT0..RT2 (and RT4's textured emission) and the samples the surface covers, or discards the fragment where the material
// cuts the surface out of every sample. Built with SPHERE_IMPOSTOR for sphere impostors
// (sphere_impostor.glsl): the surface is the sphere the fragment's cube bounds, its depth written
// here (declared depth_greater) and its samples those whose lines of sight meet it.
void writeSurface() {
    InstanceData inst = instances[inInstance];
    MaterialData mat = materials[inst.materialIndex];
#ifdef SPHERE_IMPOSTOR
    // Derivatives first, while every invocation of the quad runs.
    vec3 dx = dFdx(inWorldPosition), dy = dFdy(inWorldPosition);
    ImpostorHit sphere = impostorHit(camera.viewProjection, inst.normalMatrix, inWorldPosition, inTangent);
    uint sphereCoverage = push.sampleCount <= 1u ? (sphere.hit ? ~0u : 0u) : impostorCoverage(inst, dx, dy);
    // Misses leave at once: most of a cube's fragments (its far faces, its corners) miss. XXX: a
    // textured material's lookups in the quads along the rim then take their derivatives from
    // invocations that left (Vulkan's demote would keep them, at the cost of shading every miss).
    if (sphereCoverage == 0u) discard;
    // The pixel's centre may miss where some sample meets the rim: shade that sample's point.
    for (int s = 0; !sphere.hit && s < int(push.sampleCount); ++s)
        if ((sphereCoverage & (1u << uint(s))) != 0u) sphere = sampleImpostorHit(inst, s, dx, dy);
    gl_FragDepth = sphere.depth;
    vec3 worldPosition = sphere.position;
    vec4 tangent = impostorTangent(inst.model, sphere.normal);
    vec3 n = sphere.normal;
    bool backFacing = sphere.backFacing;
#else
    vec3 worldPosition = inWorldPosition;
    vec4 tangent = inTangent;
    vec3 n = normalize(inNormal);
    bool backFacing = !gl_FrontFacing;
#endif
    // Double-sided surfaces face the viewer; single-sided ones keep their orientation.
    if ((inst.flags & INSTANCE_DOUBLE_SIDED) != 0u && backFacing) n = -n;
    n = perturbedNormal(n, tangent, mat.textures[TEXTURE_NORMAL], normalTexture, inUv);
    vec3 albedo = albedoFromDisplayColor(inst)
                      ? displayAlbedo(inst, inColor, mat.diffuseRoughness.rgb)
                      : colorInput(mat.diffuseRoughness.rgb, mat.textures[TEXTURE_DIFFUSE], diffuseTexture, inUv);
    float roughness = scalarInput(mat.diffuseRoughness.a, mat.textures[TEXTURE_ROUGHNESS], roughnessTexture, inUv);
    float metallic = scalarInput(mat.emissiveMetallic.a, mat.textures[TEXTURE_METALLIC], metallicTexture, inUv);
    float occlusion = scalarInput(mat.opacity.z, mat.textures[TEXTURE_OCCLUSION], occlusionTexture, inUv);
    if (drawUses(MATERIAL_ANISOTROPIC) && mat.anisotropy.x > 0.0)
        principalLobe(n, roughness, tangent, mat.anisotropy.xy, worldPosition,
                      normalize(camera.position.xyz - worldPosition));
#ifndef OPAQUE_SURFACE
    uint coverage = cutoutCoverage(mat, inUv);
#ifdef SPHERE_IMPOSTOR
    coverage &= sphereCoverage;
#endif
    if (coverage == 0u) discard;
    gl_SampleMask[0] = int(coverage);
#endif
    outNormalRoughness = vec4(encodeBestFitNormal(n, fittingScale), roughness);
    outAlbedoMetallic = vec4(albedo, metallic);
    outInstance = packInstanceTarget(inInstance, occlusion);
    if (drawUses(MATERIAL_TEXTURED_EMISSION))
        outEmission = vec4(colorInput(mat.emissiveMetallic.rgb, mat.textures[TEXTURE_EMISSIVE], emissiveTexture, inUv) *
                               camera.exposureScale,
                           0.0);
}

#endif
