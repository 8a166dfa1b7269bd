#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred lighting, pixel frequency, in compute (screen-space passes run on every GPU core).
// Reads the thin G-buffer, accumulates Lambert + GGX for distant and sphere lights (shadowed
// through the shadow atlas, per pixel) plus emission into B10G11R11_UFLOAT, pre-exposed by the camera's exposure (seed 004 "HDR": keep the
// accumulation in a range the small float format holds well).
#extension GL_EXT_scalar_block_layout : require
#include "common/frame_data.glsl"
#include "common/brdf.glsl"
#include "common/best_fit_normals.glsl"
#include "common/ssao_upsample.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform Camera { CameraData camera; };
layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Materials { MaterialData materials[]; };
layout(set = 0, binding = 3, std430) readonly buffer Lights { uint lightCount; uint pad[3]; LightData lights[]; };
layout(set = 0, binding = 4) uniform sampler2D depthTexture;
layout(set = 0, binding = 5) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 6) uniform sampler2D albedoMetallicTexture;
layout(set = 0, binding = 7) uniform usampler2D instanceTexture;
layout(set = 0, binding = 8, r11f_g11f_b10f) uniform writeonly image2D lightAccumulation;
layout(set = 0, binding = 9) uniform sampler2D ambientAccessibility;
layout(set = 0, binding = 10) uniform sampler2D ambientHalfDepth;
layout(set = 0, binding = 11, std430) readonly buffer ShadowViews { ShadowViewData shadowViews[]; };
layout(set = 0, binding = 12) uniform sampler2D shadowAtlas;

#include "common/shadow_sampling.glsl"

vec3 worldPositionFromDepth(ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / camera.resolution * 2.0 - 1.0;
    vec4 p = camera.inverseViewProjection * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}

// Radiance reflected towards V from a light of irradiance `irradiance` (at normal incidence)
// arriving from L, for a light of angular radius `sinHalfAngle` seen from the point.
vec3 shade(vec3 N, vec3 V, vec3 L, vec3 irradiance, float sinHalfAngle, vec3 albedo, float metallic,
           float roughness, vec2 factors) {
    float NdotL = dot(N, L);
    if (NdotL <= 0.0) return vec3(0.0);
    float NdotV = max(dot(N, V), 1e-4);
    vec3 H = normalize(L + V);
    float NdotH = max(dot(N, H), 0.0);
    float VdotH = max(dot(V, H), 0.0);
    float alpha = alphaFromRoughness(roughness);
    // Area lights widen the lobe (Karis 2013, "sphere light normalisation"): energy is
    // conserved by the (alpha / alpha')^2 factor.
    float alphaWide = clamp(alpha + 0.5 * sinHalfAngle, 0.0, 1.0);
    float energy = (alpha * alpha) / (alphaWide * alphaWide);
    vec3 f0 = mix(vec3(0.04), albedo, metallic);
    vec3 specular = ggxDistribution(NdotH, alphaWide) * energy *
                    smithVisibilityHeightCorrelated(NdotV, NdotL, alpha) * fresnelSchlick(f0, VdotH);
    vec3 diffuse = (1.0 - metallic) * albedo / PI;
    return (diffuse * factors.x + specular * factors.y) * irradiance * NdotL;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(camera.resolution)))) return;
    uint instanceId = texelFetch(instanceTexture, pixel, 0).r;
    if (instanceId == 0u) {
        imageStore(lightAccumulation, pixel, vec4(0.0));
        return;
    }
    InstanceData inst = instances[instanceId - 1u];
    MaterialData mat = materials[inst.materialIndex];
    float depth = texelFetch(depthTexture, pixel, 0).r;
    vec4 nr = texelFetch(normalRoughnessTexture, pixel, 0);
    vec4 am = texelFetch(albedoMetallicTexture, pixel, 0);
    vec3 N = decodeBestFitNormal(nr.xyz);
    vec3 P = worldPositionFromDepth(pixel, depth);
    vec3 V = normalize(camera.position.xyz - P);

    vec3 radiance = mat.emissiveMetallic.rgb;
    float viewDistance = linearDepthFromDevice(camera.projection, depth);
    float ambientAccess = sampleAmbientAccess(ambientAccessibility, ambientHalfDepth, pixel, viewDistance);
    for (uint i = 0u; i < lightCount; ++i) {
        LightData light = lights[i];
        uint type = uint(light.positionType.w);
        if (type == LIGHT_DISTANT) {
            // UsdLux: irradiance = radiance x solid angle of the disc (precomputed on the host).
            vec3 L = -light.directionAngle.xyz;
            vec3 reflected = shade(N, V, L, light.radiance.rgb, sin(light.directionAngle.w), am.rgb, am.a, nr.a,
                                   light.factors.xy);
            if (any(greaterThan(reflected, vec3(0.0))))
                reflected *= distantLightVisibility(light.shadow, P, N, viewDistance);
            radiance += reflected;
        } else if (type == LIGHT_SPHERE) {
            vec3 toLight = light.positionType.xyz - P;
            float d2 = max(dot(toLight, toLight), 1e-8);
            float d = sqrt(d2);
            vec3 L = toLight / d;
            float r = light.radiance.a;
            // A uniform sphere of radiance L_e and radius r fully above the horizon gives
            // E = pi * L_e * (r/d)^2 * cos(theta); a point light (r folded in) follows the same law.
            vec3 irradiance = PI * light.radiance.rgb * (r * r) / d2;
            // treatAsPoint keeps the power but not the lobe widening of an extended source.
            float sinHalfAngle = light.factors.z > 0.0 ? 0.0 : clamp(r / d, 0.0, 1.0);
            vec3 reflected = shade(N, V, L, irradiance, sinHalfAngle, am.rgb, am.a, nr.a, light.factors.xy);
            if (any(greaterThan(reflected, vec3(0.0))))
                reflected *= sphereLightVisibility(light.shadow, P, N, light.positionType.xyz);
            radiance += reflected;
        } else if (type == LIGHT_DOME) {
            // A constant environment: Lambert integrates to albedo * L; GGX through the split-sum
            // pre-integration (environmentBrdf).
            vec3 f0 = mix(vec3(0.04), am.rgb, am.a);
            vec2 scaleBias = environmentBrdf(nr.a, max(dot(N, V), 1e-4));
            vec3 diffuse = (1.0 - am.a) * am.rgb;
            vec3 specular = f0 * scaleBias.x + scaleBias.y;
            radiance += ambientAccess * (diffuse * light.factors.x + specular * light.factors.y) * light.radiance.rgb;
        }
    }
    imageStore(lightAccumulation, pixel, vec4(radiance * camera.exposureScale, 1.0));
}
