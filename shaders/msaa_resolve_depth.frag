#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve, the targets a compute shader cannot write (msaa_resolve.comp does
// the rest): the depth it chose for each pixel into the single-sample depth target (ALWAYS: every
// pixel), and the mean of the sRGB albedo's samples the pixel resolves. A pixel the resolve did not
// tag is lit once with it: its samples lie on one surface (the resolve's test) but may see
// different colours of it (faces of another displayColor), and the lighting is linear in the base
// colour (bilinear where metallic varies too), so the mean keeps such a colour edge's coverage
// where sample 0 alone would alias it. Tagged pixels are lit per sample; for them the mean is the
// albedo AOV's box filter.
#include "common/frame_data.glsl"
#include "common/msaa_samples.glsl"

layout(set = 0, binding = 0) uniform sampler2DMS albedoMetallicSamples;
layout(set = 0, binding = 1) uniform sampler2D centreDepth;
// binding 2: the tagged quads, msaa_edge_mask.frag's (both draws share one descriptor set)
CAMERA_BLOCK(3);

layout(location = 0) out vec4 outAlbedoMetallic;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int sampleCount = textureSamples(albedoMetallicSamples);
    vec2 jitter = camera.clipJitter * camera.resolution * 0.5;
    vec4 sum = vec4(0.0);
    for (int s = 0; s < sampleCount; ++s)
        sum += texelFetch(albedoMetallicSamples,
                          resolvedSampleSource(pixel, s, sampleCount, camera.sampleResolve, jitter,
                                               ivec2(camera.resolution)),
                          s);
    outAlbedoMetallic = sum / float(sampleCount);
    gl_FragDepth = texelFetch(centreDepth, pixel, 0).r;
}
