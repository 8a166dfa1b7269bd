#version 460
#extension GL_GOOGLE_include_directive : require
// GPU occlusion culling, step 2 (passes/hi_z.h): the depth pyramid's levels 1 to 5 from the depth
// the early G-buffer wrote. One 16x16 workgroup per 32x32 pixels: each invocation takes the
// farthest of 2x2 pixels (of every sample under MSAA: a sample the rasteriser may cover counts),
// then the group halves its tile in shared memory four times. Pixels past the image's edge read
// the edge's: the texel that covers them covers the edge too, so the farthest depth is unchanged.
#include "common/hi_z.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

#ifdef MULTISAMPLED
layout(set = 0, binding = 0) uniform sampler2DMS depthTexture;
#else
layout(set = 0, binding = 0) uniform sampler2D depthTexture;
#endif
layout(set = 0, binding = 1, std430) writeonly buffer Pyramid { float farthest[]; };

layout(push_constant) uniform Push {
    uvec2 pixels;  // the depth's size
    uint samples;  // its samples per pixel
} push;

shared float tile[256];

float pixelFarthest(ivec2 pixel) {
    pixel = min(pixel, ivec2(push.pixels) - 1);
#ifdef MULTISAMPLED
    float depth = 0.0;
    for (int s = 0; s < int(push.samples); ++s) depth = max(depth, texelFetch(depthTexture, pixel, s).r);
    return depth;
#else
    return texelFetch(depthTexture, pixel, 0).r;
#endif
}

void store(uint level, uvec2 texel, float depth) {
    uvec2 size = hiZLevelSize(push.pixels, level);
    if (all(lessThan(texel, size))) farthest[hiZLevelOffset(push.pixels, level) + texel.y * size.x + texel.x] = depth;
}

void main() {
    uvec2 t = gl_LocalInvocationID.xy;
    uvec2 texel = gl_GlobalInvocationID.xy;
    ivec2 pixel = ivec2(texel * 2u);
    float depth = max(max(pixelFarthest(pixel), pixelFarthest(pixel + ivec2(1, 0))),
                      max(pixelFarthest(pixel + ivec2(0, 1)), pixelFarthest(pixel + ivec2(1, 1))));
    store(1u, texel, depth);
    tile[t.y * 16u + t.x] = depth;
    uint top = min(hiZTopLevel(push.pixels), 5u);
    for (uint level = 2u, side = 8u; level <= top; ++level, side >>= 1u) {
        barrier();
        bool reducing = all(lessThan(t, uvec2(side)));
        if (reducing) {
            uint i = 2u * t.y * 16u + 2u * t.x;
            depth = max(max(tile[i], tile[i + 1u]), max(tile[i + 16u], tile[i + 17u]));
        }
        barrier();
        if (reducing) {
            tile[t.y * 16u + t.x] = depth;
            store(level, gl_WorkGroupID.xy * side + t, depth);
        }
    }
}
