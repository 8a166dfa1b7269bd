// Deferred MSAA (seed 000 "Deferred MSAA"): what the custom resolve and the per-sample lighting
// agree on: the reserved stencil bit, the sample locations and when two samples differ.
#ifndef OBSCURA_MSAA_SAMPLES_GLSL
#define OBSCURA_MSAA_SAMPLES_GLSL

#include "best_fit_normals.glsl"
#include "gbuffer_discontinuity.glsl"
#include "instance_target.glsl"
#include "view_depth.glsl"

// Seed 000 "Deferred MSAA \ stencil batching": one reserved stencil bit tags the pixels lit per
// sample (clip volumes own 0x01..0x40). Mirrors passes/msaa_resolve.h kMsaaEdgeStencilBit.
const uint MSAA_EDGE_STENCIL_BIT = 0x80u;

// Vulkan's standard sample locations (the spec's table for standardSampleLocations), from the
// pixel's top-left corner in pixels: where sample s of an N-sample pixel was rasterised.
vec2 standardSampleLocation(int sampleCount, int s) {
    const vec2 two[2] = vec2[2](vec2(0.75, 0.75), vec2(0.25, 0.25));
    const vec2 four[4] = vec2[4](vec2(0.375, 0.125), vec2(0.875, 0.375), vec2(0.125, 0.625), vec2(0.625, 0.875));
    const vec2 eight[8] = vec2[8](vec2(0.5625, 0.3125), vec2(0.4375, 0.6875), vec2(0.8125, 0.5625),
                                  vec2(0.3125, 0.1875), vec2(0.1875, 0.8125), vec2(0.0625, 0.4375),
                                  vec2(0.6875, 0.9375), vec2(0.9375, 0.0625));
    if (sampleCount == 2) return two[s];
    if (sampleCount == 4) return four[s];
    if (sampleCount == 8) return eight[s];
    return vec2(0.5);
}

GBufferSample fetchGBufferSample(sampler2DMS depthSamples, sampler2DMS normalRoughnessSamples,
                                 usampler2DMS instanceSamples, mat4 projection, ivec2 pixel, int s) {
    GBufferSample g;
    g.instance = instanceIdFromTarget(texelFetch(instanceSamples, pixel, s).r);
    g.viewDistance = linearDepthFromDevice(projection, texelFetch(depthSamples, pixel, s).r);
    g.normal = decodeBestFitNormal(texelFetch(normalRoughnessSamples, pixel, s).xyz);
    return g;
}

// Whether any sample of `pixel` differs from sample 0: the per-sample mask before the quad.
bool samplesMismatch(sampler2DMS depthSamples, sampler2DMS normalRoughnessSamples, usampler2DMS instanceSamples,
                     mat4 projection, ivec2 pixel) {
    int sampleCount = textureSamples(instanceSamples);
    GBufferSample first = fetchGBufferSample(depthSamples, normalRoughnessSamples, instanceSamples, projection,
                                             pixel, 0);
    for (int s = 1; s < sampleCount; ++s)
        if (samplesDiffer(first, fetchGBufferSample(depthSamples, normalRoughnessSamples, instanceSamples,
                                                    projection, pixel, s)))
            return true;
    return false;
}

#endif
