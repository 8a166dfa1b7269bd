#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve, the per-sample mask where clip volumes need a depth/stencil
// attachment (seed 000 "custom resolve & per-sample mask" and "stencil batching"): the quads
// msaa_resolve.comp tagged get the reserved stencil bit. The pipeline writes the bit with REPLACE
// under the stencil write mask 0x80, so the clip volumes' bits survive; untagged pixels are
// discarded. (Writing stencil from a shader needs VK_EXT_shader_stencil_export, which is not core:
// discard and the stencil op do it on every device, as the seed's fallback does with clip/discard.)
// The bindings of msaa_resolve_depth.frag: both draws share one descriptor set.
layout(set = 0, binding = 1) uniform usampler2D edgeStencil;

void main() {
    if (texelFetch(edgeStencil, ivec2(gl_FragCoord.xy), 0).r == 0u) discard;
}
