#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve, the targets a compute shader cannot write (msaa_resolve.comp does
// the rest): the depth it chose for each pixel into the single-sample depth target (ALWAYS: every
// pixel), and sample 0 of the sRGB albedo, whose target re-encodes what the fetch decoded (8-bit
// values round-trip exactly).
layout(set = 0, binding = 0) uniform sampler2DMS albedoMetallicSamples;
layout(set = 0, binding = 1) uniform sampler2D centreDepth;
// binding 2: the tagged quads, msaa_edge_mask.frag's (both draws share one descriptor set)

layout(location = 0) out vec4 outAlbedoMetallic;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    outAlbedoMetallic = texelFetch(albedoMetallicSamples, pixel, 0);
    gl_FragDepth = texelFetch(centreDepth, pixel, 0).r;
}
