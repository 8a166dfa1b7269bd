#version 460
#extension GL_GOOGLE_include_directive : require
// SSAO step 1 (seed 004 "SSAO improvements": SSAO at half resolution): full-resolution depth and
// normals to one texel per 2x2 pixels. A texel takes one of its four pixels whole, never an
// average: averaged depths across a silhouette make a surface that is not there. Which pixel
// alternates in a checkerboard between the nearest and the farthest, so that both sides of a
// silhouette keep texels of their own within every 2x2 footprint for the bilateral blur and the
// upsample to match (the nearest everywhere loses thin gaps between foreground objects, the
// farthest everywhere thin foreground features).
// Depth is stored linear so that the obscurance works in view space; the normal is the G-buffer's
// best-fit normal of the same pixel, copied as it is, with which pixel of the 2x2 it was in alpha
// (index / 3) so that the obscurance puts the point exactly where it was seen.
#include "common/frame_data.glsl"
#include "common/ssao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1) uniform sampler2D depthTexture;
layout(set = 0, binding = 2) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 3, r32f) uniform writeonly image2D halfDepth;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D halfNormal;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(halfDepth)))) return;
    // Odd sizes: the last texel's missing pixels repeat the image's edge.
    ivec2 lastPixel = textureSize(depthTexture, 0) - 1;
    bool takeNearest = ((texel.x + texel.y) & 1) == 0;
    int chosen = 0;
    float chosenDepth = texelFetch(depthTexture, min(texel * 2, lastPixel), 0).r;
    for (int i = 1; i < 4; ++i) {
        float depth = texelFetch(depthTexture, min(texel * 2 + ivec2(i & 1, i >> 1), lastPixel), 0).r;
        // Device depth grows with distance under both projections: no need to linearise to compare.
        if (takeNearest ? depth < chosenDepth : depth > chosenDepth) {
            chosen = i;
            chosenDepth = depth;
        }
    }
    vec3 normal = texelFetch(normalRoughnessTexture, min(texel * 2 + ivec2(chosen & 1, chosen >> 1), lastPixel), 0).rgb;
    imageStore(halfDepth, texel, vec4(linearDepthFromDevice(camera.projection, chosenDepth)));
    imageStore(halfNormal, texel, vec4(normal, float(chosen) / 3.0));
}
