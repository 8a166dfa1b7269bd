#version 460
#extension GL_GOOGLE_include_directive : require
// Edge AA, step 3 of 3: each pixel takes of its neighbours across its edges what the weights give
// (SMAA's neighbourhood blending: the edges of one orientation, the stronger, per pixel). The
// weights are areas, so the mix is made in linear radiance: the box filter over the reconstructed
// silhouette, the supersampled image's own definition. Seed 004 chooses between linear and gamma
// blending from the frame's histogram (for LDR targets); the MSAA resolve's tone-mapped weights
// (common/hdr_resolve.glsl) were measured here too and lose against the supersampled truth, in
// linear and in tone-mapped terms (tests/delegate/hybrid_aa_test.cpp; docs/ARCHITECTURE.md).
#include "common/edge_aa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D color;    // HDR, coverage in alpha (nearest)
layout(set = 0, binding = 1) uniform sampler2D weights;  // edge_aa_weights.comp (nearest)
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D blended;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(blended);
    if (any(greaterThanEqual(p, size))) return;
    vec4 centre = texelFetch(color, p, 0);
    vec4 own = texelFetch(weights, p, 0);
    // What the pixel takes from above, below, left and right: its own top and left edges' x and z,
    // the bottom neighbour's top edge's y, the right neighbour's left edge's w.
    float fromBelow = p.y + 1 < size.y ? texelFetch(weights, p + ivec2(0, 1), 0).y : 0.0;
    float fromRight = p.x + 1 < size.x ? texelFetch(weights, p + ivec2(1, 0), 0).w : 0.0;
    bool vertical = max(own.x, fromBelow) >= max(own.z, fromRight);
    vec2 w = vertical ? vec2(own.x, fromBelow) : vec2(own.z, fromRight);
    if (w.x + w.y <= 0.0) {
        imageStore(blended, p, centre);
        return;
    }
    ivec2 step = vertical ? ivec2(0, 1) : ivec2(1, 0);
    vec4 a = texelFetch(color, clamp(p - step, ivec2(0), size - 1), 0);
    vec4 b = texelFetch(color, clamp(p + step, ivec2(0), size - 1), 0);
    vec3 mixWeights = vec3(1.0 - w.x - w.y, w.x, w.y);
    vec4 mixed = mixWeights.x * centre + mixWeights.y * a + mixWeights.z * b;
    imageStore(blended, p, mixed);
}
