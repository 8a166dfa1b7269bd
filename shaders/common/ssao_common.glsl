// View-space helpers shared by the SSAO passes (passes/ssao.cpp) and their upsample in the
// lighting pass (ssao_upsample.glsl).
#ifndef OBSCURA_SSAO_COMMON_GLSL
#define OBSCURA_SSAO_COMMON_GLSL

#include "common/view_depth.glsl"

// View-space position seen at normalised device coordinates `ndc` at `linearDepth`. USD cameras
// have no skew: clip x depends on view x and z only, clip y on view y and z only.
vec3 viewPositionFromLinearDepth(mat4 projection, vec2 ndc, float linearDepth) {
    float z = -linearDepth;
    float w = projection[2][3] * z + projection[3][3];
    vec2 xy = (ndc * w - vec2(projection[2][0], projection[2][1]) * z - vec2(projection[3][0], projection[3][1])) /
              vec2(projection[0][0], projection[1][1]);
    return vec3(xy, z);
}

// SSAO at half resolution (seed 004 "SSAO improvements"): a half-resolution texel takes one of its
// four full-resolution pixels whole, never an average: averaged depths across a silhouette make a
// surface that is not there. Which pixel alternates in a checkerboard between the nearest and the
// farthest, so that both sides of a silhouette keep texels of their own within every 2x2 footprint
// for the bilateral blur and the upsample to match (the nearest everywhere loses thin gaps between
// foreground objects, the farthest everywhere thin foreground features).
struct HeldPixel {
    int index;          // in the 2x2 block: x = index & 1, y = index >> 1
    float deviceDepth;  // the G-buffer's
};
HeldPixel heldPixel(sampler2D depthTexture, ivec2 texel) {
    // Odd sizes: the last texel's missing pixels repeat the image's edge.
    ivec2 lastPixel = textureSize(depthTexture, 0) - 1;
    bool takeNearest = ((texel.x + texel.y) & 1) == 0;
    HeldPixel held = HeldPixel(0, texelFetch(depthTexture, min(texel * 2, lastPixel), 0).r);
    for (int i = 1; i < 4; ++i) {
        float depth = texelFetch(depthTexture, min(texel * 2 + ivec2(i & 1, i >> 1), lastPixel), 0).r;
        // Device depth grows with distance under both projections: no need to linearise to compare.
        if (takeNearest ? depth < held.deviceDepth : depth > held.deviceDepth) held = HeldPixel(i, depth);
    }
    return held;
}

// NDC of the full-resolution pixel whose depth and normal a half-resolution texel holds: its index
// in the 2x2 block is stored as index / 3 (ssao_obscurance.comp).
vec2 heldPixelNdc(ivec2 texel, int index, vec2 resolution) {
    ivec2 pixel = min(texel * 2 + ivec2(index & 1, index >> 1), ivec2(resolution) - 1);
    return (vec2(pixel) + 0.5) / resolution * 2.0 - 1.0;
}
vec2 heldPixelNdc(ivec2 texel, float storedIndex, vec2 resolution) {
    return heldPixelNdc(texel, int(round(storedIndex * 3.0)), resolution);
}

// Weight of a neighbour in the bilateral blur and upsample by how far its depth lies from the one
// expected: 1 when equal, falling linearly to 0 at SSAO_DEPTH_TOLERANCE of the reference depth
// (relative, so that an edge reads the same at every distance).
const float SSAO_DEPTH_TOLERANCE = 0.05;
float ssaoDepthWeight(float depthDifference, float referenceDepth) {
    return max(1.0 - abs(depthDifference) / (SSAO_DEPTH_TOLERANCE * referenceDepth), 0.0);
}

#endif
