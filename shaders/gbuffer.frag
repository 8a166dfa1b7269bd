#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, fragment stage: the thin G-buffer of seed 004 ("G-Buffer layout"):
//   RT0 RGBA8  best-fit normal (24 bits) + roughness (8 bits)
//   RT1 RGBA8 sRGB  albedo + metallic
//   RT2 R32UI  instance index + 1 (0: nothing drawn) for per-prim data and the primId AOV
#include "common/frame_data.glsl"
#include "common/best_fit_normals.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inColor;
layout(location = 2) in vec3 inWorldPosition;
layout(location = 3) flat in uint inInstance;
layout(location = 4) in vec2 inUv;

layout(set = 0, binding = 0, std140) uniform Camera { CameraData camera; };
layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Materials { MaterialData materials[]; };
layout(set = 0, binding = 3) uniform sampler2D fittingScale;
// The draw's material textures, pushed per draw (white where an input is constant).
layout(set = 1, binding = 0) uniform sampler2D diffuseTexture;
layout(set = 1, binding = 1) uniform sampler2D roughnessTexture;
layout(set = 1, binding = 2) uniform sampler2D metallicTexture;
layout(set = 1, binding = 3) uniform sampler2D opacityTexture;

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outAlbedoMetallic;
layout(location = 2) out uint outInstance;

// UsdUVTexture (UsdPreviewSurface spec): texel * scale + bias.
vec4 sampleTexture(MaterialTexture t, sampler2D tex) { return texture(tex, inUv) * t.scale + t.bias; }

vec3 colorInput(vec3 constant, MaterialTexture t, sampler2D tex) {
    if (t.sampled == 0u) return constant;
    vec4 v = sampleTexture(t, tex);
    return t.channel == TEXTURE_CHANNEL_RGB ? v.rgb : vec3(v[t.channel]);
}

// Float inputs fed from the rgb output read its first component.
float scalarInput(float constant, MaterialTexture t, sampler2D tex) {
    if (t.sampled == 0u) return constant;
    return clamp(sampleTexture(t, tex)[t.channel == TEXTURE_CHANNEL_RGB ? 0u : t.channel], 0.0, 1.0);
}

void main() {
    InstanceData inst = instances[inInstance];
    MaterialData mat = materials[inst.materialIndex];
    vec3 n = normalize(inNormal);
    // Double-sided surfaces face the viewer; single-sided ones keep their orientation.
    if ((inst.flags & INSTANCE_DOUBLE_SIDED) != 0u && !gl_FrontFacing) n = -n;
    vec3 albedo = (inst.flags & INSTANCE_VERTEX_COLOR) != 0u
                      ? inColor
                      : colorInput(mat.diffuseRoughness.rgb, mat.textures[TEXTURE_DIFFUSE], diffuseTexture);
    float roughness = scalarInput(mat.diffuseRoughness.a, mat.textures[TEXTURE_ROUGHNESS], roughnessTexture);
    float metallic = scalarInput(mat.emissiveMetallic.a, mat.textures[TEXTURE_METALLIC], metallicTexture);
    // UsdPreviewSurface opacityThreshold: above 0, opacity is a cut-out mask. Discarded last, so
    // every implicit-LOD sample above runs in uniform control flow.
    float threshold = mat.opacity.y;
    float opacity = threshold > 0.0 ? scalarInput(mat.opacity.x, mat.textures[TEXTURE_OPACITY], opacityTexture) : 1.0;
    if (opacity < threshold) discard;
    outNormalRoughness = vec4(encodeBestFitNormal(n, fittingScale), roughness);
    outAlbedoMetallic = vec4(albedo, metallic);
    outInstance = inInstance + 1u;
}
