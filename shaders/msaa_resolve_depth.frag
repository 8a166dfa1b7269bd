#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve, where clip volumes need a depth/stencil attachment to test and mark
// (passes/msaa_resolve.cpp): the depth msaa_resolve.comp chose for each pixel into the single-sample
// depth target (ALWAYS: every pixel).
layout(set = 0, binding = 0) uniform sampler2D centreDepth;
// binding 1: the stencil value msaa_edge_mask.frag reads (both draws share one descriptor set)

void main() { gl_FragDepth = texelFetch(centreDepth, ivec2(gl_FragCoord.xy), 0).r; }
