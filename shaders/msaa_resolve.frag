#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve, first half (seed 000 "Deferred MSAA \ custom resolve & per-sample
// mask": "pre-resolves sample 0, for pixel frequency passes"): copies sample 0 of every G-buffer
// target into the single-sample G-buffer. Every pass that works per pixel (SSAO, lighting of
// untagged pixels, temporal AA, depth of field, AOVs) reads those. Averaging would be wrong for
// ids and normals and would invent depths no surface has.
// Depth is the exception where the samples agree: the rasteriser interpolates depth at each
// sample's own location while colours come from the pixel centre, and sample 0 of the standard
// pattern lies (-1/8, -3/8) pixel off the centre, so its depth put at the centre moves the point
// along the view ray by a sizeable step on grazing surfaces (enough for a shadow map to shadow a
// lit floor). Device depth is affine in window position across a triangle and the standard
// locations of 2, 4 and 8 samples average to the pixel centre, so the mean of alike samples is
// exactly the depth at the centre; where samples differ, sample 0's depth (an existing surface).
#include "common/frame_data.glsl"
#include "common/msaa_samples.glsl"

layout(set = 0, binding = 0) uniform sampler2DMS depthSamples;
layout(set = 0, binding = 1) uniform sampler2DMS normalRoughnessSamples;
layout(set = 0, binding = 2) uniform sampler2DMS albedoMetallicSamples;
layout(set = 0, binding = 3) uniform usampler2DMS instanceSamples;
CAMERA_BLOCK(4);

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outAlbedoMetallic;
layout(location = 2) out uint outInstance;
// Built twice (cmake variants): with VELOCITY_TARGET for a G-buffer with motion blur's velocity.
#ifdef VELOCITY_TARGET
layout(set = 0, binding = 5) uniform sampler2DMS velocitySamples;
layout(location = 3) out vec2 outVelocity;
layout(location = 4) out float outMaxDepth;
#else
layout(location = 3) out float outMaxDepth;
#endif

float pixelCentreDepth(ivec2 pixel) {
    if (samplesMismatch(depthSamples, normalRoughnessSamples, instanceSamples, camera.projection, pixel))
        return texelFetch(depthSamples, pixel, 0).r;
    int sampleCount = textureSamples(depthSamples);
    float sum = 0.0;
    for (int s = 0; s < sampleCount; ++s) sum += texelFetch(depthSamples, pixel, s).r;
    return sum / float(sampleCount);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    outNormalRoughness = texelFetch(normalRoughnessSamples, pixel, 0);
    // The sRGB target re-encodes what the fetch decoded: 8-bit values round-trip exactly.
    outAlbedoMetallic = texelFetch(albedoMetallicSamples, pixel, 0);
    outInstance = texelFetch(instanceSamples, pixel, 0).r;
#ifdef VELOCITY_TARGET
    outVelocity = texelFetch(velocitySamples, pixel, 0).rg;
#endif
    gl_FragDepth = pixelCentreDepth(pixel);
    // Seed 000 "performance shortcuts (2)": the farthest sample, for the transparents' depth test
    // and fade (passes/transparent.h).
    float farthest = 0.0;
    for (int s = 0; s < textureSamples(depthSamples); ++s) farthest = max(farthest, texelFetch(depthSamples, pixel, s).r);
    outMaxDepth = farthest;
}
