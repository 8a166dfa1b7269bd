// G-buffer pass, fragment stage shared by the static and the moving draws: the thin G-buffer of
// seed 004 ("G-Buffer layout"):
//   RT0 RGBA8  best-fit normal (24 bits) + roughness (8 bits)
//   RT1 RGBA8 sRGB  albedo + metallic
//   RT2 R32UI  instance index + 1 (0: nothing drawn) for per-prim data and the primId AOV, and the
//              material's occlusion in its top 8 bits (instance_target.glsl)
// (and, with motion blur, RT3 RG16F velocity, written by moving draws only: gbuffer_moving.frag).
#ifndef OBSCURA_GBUFFER_SURFACE_GLSL
#define OBSCURA_GBUFFER_SURFACE_GLSL

#include "frame_data.glsl"
#include "best_fit_normals.glsl"
#include "material_inputs.glsl"
#include "instance_target.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inColor;
layout(location = 2) in vec3 inWorldPosition;
layout(location = 3) flat in uint inInstance;
layout(location = 4) in vec2 inUv;
layout(location = 5) in vec4 inTangent;

layout(set = 0, binding = 0, std140) uniform Camera { CameraData camera; };
layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Materials { MaterialData materials[]; };
layout(set = 0, binding = 3) uniform sampler2D fittingScale;
// The draw's material textures, pushed per draw (white where an input is constant).
layout(set = 1, binding = 0) uniform sampler2D diffuseTexture;
layout(set = 1, binding = 1) uniform sampler2D roughnessTexture;
layout(set = 1, binding = 2) uniform sampler2D metallicTexture;
layout(set = 1, binding = 3) uniform sampler2D opacityTexture;
layout(set = 1, binding = 4) uniform sampler2D normalTexture;
layout(set = 1, binding = 5) uniform sampler2D occlusionTexture;

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outAlbedoMetallic;
layout(location = 2) out uint outInstance;

// Writes RT0..RT2, or discards the fragment where the material cuts the surface out.
void writeSurface() {
    InstanceData inst = instances[inInstance];
    MaterialData mat = materials[inst.materialIndex];
    vec3 n = normalize(inNormal);
    // Double-sided surfaces face the viewer; single-sided ones keep their orientation.
    if ((inst.flags & INSTANCE_DOUBLE_SIDED) != 0u && !gl_FrontFacing) n = -n;
    n = perturbedNormal(n, inTangent, mat.textures[TEXTURE_NORMAL], normalTexture, inUv);
    vec3 albedo = (inst.flags & INSTANCE_VERTEX_COLOR) != 0u
                      ? inColor
                      : colorInput(mat.diffuseRoughness.rgb, mat.textures[TEXTURE_DIFFUSE], diffuseTexture, inUv);
    float roughness = scalarInput(mat.diffuseRoughness.a, mat.textures[TEXTURE_ROUGHNESS], roughnessTexture, inUv);
    float metallic = scalarInput(mat.emissiveMetallic.a, mat.textures[TEXTURE_METALLIC], metallicTexture, inUv);
    float occlusion = scalarInput(mat.opacity.z, mat.textures[TEXTURE_OCCLUSION], occlusionTexture, inUv);
    if (cutOut(mat, opacityTexture, inUv)) discard;
    outNormalRoughness = vec4(encodeBestFitNormal(n, fittingScale), roughness);
    outAlbedoMetallic = vec4(albedo, metallic);
    outInstance = packInstanceTarget(inInstance, occlusion);
}

#endif
