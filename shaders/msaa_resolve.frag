#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve, first half (seed 000 "Deferred MSAA \ custom resolve & per-sample
// mask": "pre-resolves sample 0, for pixel frequency passes"): copies sample 0 of every G-buffer
// target into the single-sample G-buffer, depth through gl_FragDepth. Every pass that works per
// pixel (SSAO, lighting of untagged pixels, temporal AA, depth of field, AOVs) reads those.
// Averaging would be wrong for ids and normals and would invent depths no surface has.

layout(set = 0, binding = 0) uniform sampler2DMS depthSamples;
layout(set = 0, binding = 1) uniform sampler2DMS normalRoughnessSamples;
layout(set = 0, binding = 2) uniform sampler2DMS albedoMetallicSamples;
layout(set = 0, binding = 3) uniform usampler2DMS instanceSamples;

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outAlbedoMetallic;
layout(location = 2) out uint outInstance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    outNormalRoughness = texelFetch(normalRoughnessSamples, pixel, 0);
    // The sRGB target re-encodes what the fetch decoded: 8-bit values round-trip exactly.
    outAlbedoMetallic = texelFetch(albedoMetallicSamples, pixel, 0);
    outInstance = texelFetch(instanceSamples, pixel, 0).r;
    gl_FragDepth = texelFetch(depthSamples, pixel, 0).r;
}
