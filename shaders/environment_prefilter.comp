#version 460
#extension GL_GOOGLE_include_directive : require
// One level of a textured dome's prefiltered specular chain (split sum, Karis 2013 "Real shading
// in Unreal Engine 4": the environment convolved with the GGX lobe of the level's roughness,
// N = V = R, samples weighted by N.L). Level 0 is the mirror: the source resampled. Rougher
// levels take GGX importance samples, each read from the source mip whose texels cover the
// sample's share of the lobe's solid angle (filtered importance sampling, Colbert & Krivanek
// 2007, GPU Gems 3 ch. 20). 256 samples: at roughness 1 over a checker of 45-degree squares, 64 of
// them miss the lobe's mean by 2.2% (tests/delegate/dome_texture_test.cpp), 256 by 0.8%; the
// prefilter runs once per texture.
#include "common/environment_map.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D source;  // latlong radiance, full mip chain
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D level;

layout(push_constant) uniform Push {
    float roughness;            // perceptual roughness of this level
    float mirrorLod;            // level 0: the source mip as wide as the output
    float sourceTexelSolidAngle;  // 4 pi / texels of the source's level 0
    float sourceLastLod;
} push;

const uint SAMPLE_COUNT = 256u;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(level);
    if (any(greaterThanEqual(texel, size))) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(size);
    if (push.roughness <= 0.0) {
        imageStore(level, texel, vec4(textureLod(source, uv, push.mirrorLod).rgb, 1.0));
        return;
    }
    vec3 N = latlongDirection(uv);
    float alpha = push.roughness * push.roughness;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < SAMPLE_COUNT; ++i) {
        vec3 H = importanceSampleGgx(hammersley(i, SAMPLE_COUNT), alpha, N);
        vec3 L = 2.0 * dot(N, H) * H - N;
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        // pdf(L) = D(H) (N.H) / (4 V.H) = D(H) / 4 with V = N.
        float pdf = ggxDistribution(max(dot(N, H), 0.0), alpha) * 0.25;
        float sampleSolidAngle = 1.0 / (float(SAMPLE_COUNT) * pdf + 1e-6);
        float lod = clamp(0.5 * log2(sampleSolidAngle / push.sourceTexelSolidAngle) + 1.0, 0.0, push.sourceLastLod);
        sum += textureLod(source, latlongUv(L), lod).rgb * NdotL;
        weight += NdotL;
    }
    imageStore(level, texel, vec4(sum / max(weight, 1e-6), 1.0));
}
