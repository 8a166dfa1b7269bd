#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred lighting, pixel frequency, in compute (screen-space passes run on every GPU core).
// Tiled light culling (Andersson 2011, "DirectX 11 rendering in Battlefield 3"): each 16x16 tile
// bounds its pixels' depths, keeps the local lights whose influence sphere touches that box, then
// every pixel shades with its tile's list, each light's share through its shadow maps (per pixel,
// shadow_sampling.glsl). Accumulates into B10G11R11_UFLOAT, pre-exposed by the camera's exposure
// (seed 004 "HDR": keep the accumulation in a range the small float format holds).
#extension GL_EXT_scalar_block_layout : require
#include "common/frame_data.glsl"
#include "common/light_evaluation.glsl"
#include "common/best_fit_normals.glsl"
#include "common/ssao_upsample.glsl"
#include "common/environment_map.glsl"
#include "common/instance_target.glsl"

const uint TILE_SIZE = 16u;
const uint MAX_TILE_LIGHTS = 1024u;  // lights beyond this many in one tile are dropped
layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

layout(set = 0, binding = 0, std140) uniform Camera { CameraData camera; };
layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Materials { MaterialData materials[]; };
layout(set = 0, binding = 3, std430) readonly buffer Lights { uint lightCount; uint pad[3]; LightData lights[]; };
layout(set = 0, binding = 4) uniform sampler2D depthTexture;
layout(set = 0, binding = 5) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 6) uniform sampler2D albedoMetallicTexture;
layout(set = 0, binding = 7) uniform usampler2D instanceTexture;
// B10G11R11_UFLOAT or RGBA16F (render setting lighting:halfFloat): written without a format.
layout(set = 0, binding = 8) uniform writeonly image2D lightAccumulation;
layout(set = 0, binding = 9) uniform sampler2D ambientAccessibility;
layout(set = 0, binding = 10) uniform sampler2D ambientHalfDepth;
layout(set = 0, binding = 11, std430) readonly buffer ShadowViews { ShadowViewData shadowViews[]; };
layout(set = 0, binding = 12) uniform sampler2D shadowAtlas;
// The G-buffer's stencil: bits 0x01..0x40 mark surfaces inside the clip volumes (clip_volumes.cpp).
layout(set = 0, binding = 13) uniform usampler2D clipStencil;
// The textured dome (a 1x1 black image and zero coefficients without one).
layout(set = 0, binding = 14, std140) uniform Environment { EnvironmentData environment; };
layout(set = 0, binding = 15, std430) readonly buffer EnvironmentIrradiance { vec4 irradianceSh[SH_COEFFICIENTS]; };
layout(set = 0, binding = 16) uniform sampler2D prefilteredEnvironment;

#include "common/scene_lighting.glsl"

shared uint tileMinDepthBits;
shared uint tileMaxDepthBits;
shared uint tileLightCount;
shared uint tileLights[MAX_TILE_LIGHTS];
shared vec3 tileBoxMin;
shared vec3 tileBoxMax;

vec3 unproject(mat4 inverseMatrix, vec2 ndc, float depth) {
    vec4 p = inverseMatrix * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}

// Sphere against the tile's view-space box (tighter than the four side planes for thin tiles).
bool touchesTile(LightData light) {
    if (!isLocalLight(light)) return true;
    vec3 centre = (camera.view * vec4(light.positionType.xyz, 1.0)).xyz;
    vec3 nearest = clamp(centre, tileBoxMin, tileBoxMax);
    vec3 d = centre - nearest;
    return dot(d, d) <= light.factors.w * light.factors.w;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(pixel, ivec2(camera.resolution)));
    uint instanceTarget = inside ? texelFetch(instanceTexture, pixel, 0).r : 0u;
    uint instanceId = instanceIdFromTarget(instanceTarget);
    float depth = inside ? texelFetch(depthTexture, pixel, 0).r : 1.0;

    if (gl_LocalInvocationIndex == 0u) {
        tileMinDepthBits = floatBitsToUint(1.0);
        tileMaxDepthBits = 0u;
        tileLightCount = 0u;
    }
    barrier();
    // Depths are non-negative, so their bit patterns order like the floats.
    if (instanceId != 0u) {
        atomicMin(tileMinDepthBits, floatBitsToUint(depth));
        atomicMax(tileMaxDepthBits, floatBitsToUint(depth));
    }
    barrier();
    bool tileHasSurface = tileMinDepthBits <= tileMaxDepthBits;
    if (gl_LocalInvocationIndex == 0u && tileHasSurface) {
        vec2 tileMin = vec2(gl_WorkGroupID.xy * TILE_SIZE) / camera.resolution * 2.0 - 1.0;
        vec2 tileMax = vec2((gl_WorkGroupID.xy + 1u) * TILE_SIZE) / camera.resolution * 2.0 - 1.0;
        float depths[2] = float[2](uintBitsToFloat(tileMinDepthBits), uintBitsToFloat(tileMaxDepthBits));
        vec3 lo = vec3(1e30), hi = vec3(-1e30);
        for (int i = 0; i < 8; ++i) {
            vec2 ndc = vec2((i & 1) != 0 ? tileMax.x : tileMin.x, (i & 2) != 0 ? tileMax.y : tileMin.y);
            vec3 corner = unproject(camera.inverseProjection, ndc, depths[i >> 2]);
            lo = min(lo, corner);
            hi = max(hi, corner);
        }
        tileBoxMin = lo;
        tileBoxMax = hi;
    }
    barrier();
    if (tileHasSurface) {
        for (uint i = gl_LocalInvocationIndex; i < lightCount; i += TILE_SIZE * TILE_SIZE) {
            if (!touchesTile(lights[i])) continue;
            uint slot = atomicAdd(tileLightCount, 1u);
            if (slot < MAX_TILE_LIGHTS) tileLights[slot] = i;
        }
    }
    barrier();
    if (!inside) return;
    if (instanceId == 0u) {
        imageStore(lightAccumulation, pixel, vec4(0.0));
        return;
    }

    InstanceData inst = instances[instanceId - 1u];
    MaterialData mat = materials[inst.materialIndex];
    vec4 nr = texelFetch(normalRoughnessTexture, pixel, 0);
    vec4 am = texelFetch(albedoMetallicTexture, pixel, 0);
    vec2 ndc = (vec2(pixel) + 0.5) / camera.resolution * 2.0 - 1.0;
    SurfacePoint s = surfaceFromMaterial(mat, am.rgb, am.a);
    s.P = unproject(camera.inverseViewProjection, ndc, depth);
    s.N = decodeBestFitNormal(nr.xyz);
    s.V = normalize(camera.position.xyz - s.P);
    s.roughness = nr.a;
    float viewDistance = linearDepthFromDevice(camera.projection, depth);
    float screenSpaceAccess = sampleAmbientAccess(ambientAccessibility, ambientHalfDepth, pixel, viewDistance);
    s.ambientAccess = ambientAccessWithOcclusion(screenSpaceAccess, occlusionFromTarget(instanceTarget));
    s.environment = sampleEnvironment(s);

    vec3 radiance = mat.emissiveMetallic.rgb;
    uint insideClipVolumes = texelFetch(clipStencil, pixel, 0).r;
    uint count = min(tileLightCount, MAX_TILE_LIGHTS);
    for (uint i = 0u; i < count; ++i) {
        LightData light = lights[tileLights[i]];
        // A clipped light reaches only surfaces inside its volume (seed 004 "clip volumes").
        if (light.shadow.w != 0u && (insideClipVolumes & light.shadow.w) == 0u) continue;
        radiance += reflectShadowedLight(s, light, viewDistance);
    }
    imageStore(lightAccumulation, pixel, vec4(radiance * camera.exposureScale, 1.0));
}
