// View-space helpers shared by the SSAO passes (passes/ssao.cpp) and their upsample in the
// lighting pass (ssao_upsample.glsl).
#ifndef OBSCURA_SSAO_COMMON_GLSL
#define OBSCURA_SSAO_COMMON_GLSL

// Distance along the view axis (the camera looks down -z) of a device depth. Solves
// depth = (A z + B) / (C z + D) for the view-space z, which covers the perspective and the
// orthographic projections of delegate/prims/camera.cpp alike.
float linearDepthFromDevice(mat4 projection, float depth) {
    float a = projection[2][2], b = projection[3][2], c = projection[2][3], d = projection[3][3];
    return (b - depth * d) / (a - depth * c);
}

// View-space position seen at normalised device coordinates `ndc` at `linearDepth`. USD cameras
// have no skew: clip x depends on view x and z only, clip y on view y and z only.
vec3 viewPositionFromLinearDepth(mat4 projection, vec2 ndc, float linearDepth) {
    float z = -linearDepth;
    float w = projection[2][3] * z + projection[3][3];
    vec2 xy = (ndc * w - vec2(projection[2][0], projection[2][1]) * z - vec2(projection[3][0], projection[3][1])) /
              vec2(projection[0][0], projection[1][1]);
    return vec3(xy, z);
}

// NDC of the full-resolution pixel whose depth and normal a half-resolution texel holds: its index
// in the 2x2 block is stored as index / 3 (ssao_downsample.comp).
vec2 heldPixelNdc(ivec2 texel, float storedIndex, vec2 resolution) {
    int index = int(round(storedIndex * 3.0));
    ivec2 pixel = min(texel * 2 + ivec2(index & 1, index >> 1), ivec2(resolution) - 1);
    return (vec2(pixel) + 0.5) / resolution * 2.0 - 1.0;
}

// Weight of a neighbour in the bilateral blur and upsample by how far its depth lies from the one
// expected: 1 when equal, falling linearly to 0 at SSAO_DEPTH_TOLERANCE of the reference depth
// (relative, so that an edge reads the same at every distance).
const float SSAO_DEPTH_TOLERANCE = 0.05;
float ssaoDepthWeight(float depthDifference, float referenceDepth) {
    return max(1.0 - abs(depthDifference) / (SSAO_DEPTH_TOLERANCE * referenceDepth), 0.0);
}

#endif
