#version 460
#extension GL_GOOGLE_include_directive : require
// Edge AA, step 2 of 3: blending weights by morphological reconstruction (Reshetov 2009, "Morphological
// antialiasing"; Jimenez et al. 2011, "Practical morphological anti-aliasing" and SMAA). For the
// edge along each pixel's top (and left) side: search along it both ways for its ends, read the
// crossing edges there to tell the pattern (L, Z, U), and reconstruct the silhouette the staircase
// stands for: a line from each end's step (half a pixel across the edge, towards the side its
// crossing edge lies on) — straight from end to end for a Z, down to the edge at the middle for an
// L or a U half, as SMAA's area texture. The area between that line and the edge within the
// pixel's span is how much each side's colour covers of the other's pixel. Computed exactly here
// rather than looked up in an area texture (no texture to make; the lookups were the point on
// 2011 hardware). Diagonal patterns and SMAA's corner detection are left out.
#include "common/edge_aa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D edges;  // r: left side, g: top side (nearest)
// x, y: the top edge's areas: the pixel takes x of the pixel above, the pixel above takes y of it;
// z, w: the same for the left edge and the pixel to the left.
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D weights;

// How far the ends are searched for, each way (SMAA's default reach: 16 steps of 2 pixels).
const int MAX_SEARCH = 32;

// Pixels further along `direction` from p whose `side` edge continues the edge, up to MAX_SEARCH.
int edgeRun(ivec2 p, ivec2 direction, int side, ivec2 size) {
    int n = 0;
    for (; n < MAX_SEARCH; ++n) {
        ivec2 q = p + direction * (n + 1);
        if (!insideImage(q, size) || texelFetch(edges, q, 0)[side] < 0.5) break;
    }
    return n;
}

float edgeAt(ivec2 q, int side, ivec2 size) { return insideImage(q, size) ? texelFetch(edges, q, 0)[side] : 0.0; }

// The line's height at an end, across the edge (+ towards the pixel's side, - towards its
// neighbour's), from the crossing edges at that end: one on the pixel's side only: +1/2; on the
// neighbour's only: -1/2; none or both: 0 (nothing tells the slope).
float endHeight(ivec2 boundary, ivec2 across, int crossingSide, ivec2 size) {
    return 0.5 * (edgeAt(boundary, crossingSide, size) - edgeAt(boundary - across, crossingSide, size));
}

// The reconstructed line's height at t along an edge of length d whose ends are at h0 (t = 0) and
// h1 (t = d).
float lineHeight(float t, float d, float h0, float h1) {
    if (h0 * h1 < 0.0) return mix(h0, h1, t / d);  // Z: one line from step to step
    return t < 0.5 * d ? h0 * (1.0 - 2.0 * t / d) : h1 * (2.0 * t / d - 1.0);  // L, U: to the middle
}

// Area above (x) and below (y) zero of a linear piece from y0 to y1 over a width w.
vec2 signedAreas(float y0, float y1, float w) {
    if (y0 * y1 >= 0.0) {
        float a = 0.5 * (y0 + y1) * w;
        return vec2(max(a, 0.0), max(-a, 0.0));
    }
    float crossing = w * y0 / (y0 - y1);
    vec2 pieces = 0.5 * vec2(y0 * crossing, y1 * (w - crossing));
    return vec2(max(pieces.x, 0.0) + max(pieces.y, 0.0), max(-pieces.x, 0.0) + max(-pieces.y, 0.0));
}

// The areas for the edge along the pixel's side `side` (1: top, 0: left): x for the pixel (the
// neighbour's colour reaching into it), y for the neighbour (the pixel's reaching into it).
vec2 edgeWeights(ivec2 p, int side, ivec2 size) {
    if (texelFetch(edges, p, 0)[side] < 0.5) return vec2(0.0);
    ivec2 along = side == 1 ? ivec2(1, 0) : ivec2(0, 1);
    ivec2 across = ivec2(1) - along;
    int crossingSide = 1 - side;
    int before = edgeRun(p, -along, side, size), after = edgeRun(p, along, side, size);
    float h0 = before < MAX_SEARCH ? endHeight(p - along * before, across, crossingSide, size) : 0.0;
    float h1 = after < MAX_SEARCH ? endHeight(p + along * (after + 1), across, crossingSide, size) : 0.0;
    float d = float(before + after + 1), a = float(before), b = a + 1.0, middle = 0.5 * d;
    if (h0 * h1 < 0.0 || b <= middle || a >= middle)
        return signedAreas(lineHeight(a, d, h0, h1), lineHeight(b, d, h0, h1), 1.0);
    // The pixel spans the middle, where an L or U line meets the edge.
    return signedAreas(lineHeight(a, d, h0, h1), 0.0, middle - a) + signedAreas(0.0, lineHeight(b, d, h0, h1), b - middle);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(weights);
    if (any(greaterThanEqual(p, size))) return;
    imageStore(weights, p, vec4(edgeWeights(p, 1, size), edgeWeights(p, 0, size)));
}
