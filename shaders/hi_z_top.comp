#version 460
#extension GL_GOOGLE_include_directive : require
// GPU occlusion culling, step 2 continued (passes/hi_z.h): the depth pyramid's levels above 5,
// each from the one below, by one workgroup (level 5 is 60x34 texels at 1080p). A child index past
// the level below's edge reads its edge texel, which the parent covers too.
#include "common/hi_z.glsl"

layout(local_size_x = 256) in;

layout(set = 0, binding = 0, std430) coherent buffer Pyramid { float farthest[]; };

layout(push_constant) uniform Push {
    uvec2 pixels;  // the depth's size
} push;

void main() {
    uint top = hiZTopLevel(push.pixels);
    for (uint level = 6u; level <= top; ++level) {
        uvec2 below = hiZLevelSize(push.pixels, level - 1u);
        uint belowOffset = hiZLevelOffset(push.pixels, level - 1u);
        uvec2 size = hiZLevelSize(push.pixels, level);
        uint offset = belowOffset + below.x * below.y;
        for (uint i = gl_LocalInvocationIndex; i < size.x * size.y; i += 256u) {
            uvec2 texel = uvec2(i % size.x, i / size.x);
            uvec2 child = texel * 2u;
            uvec2 last = below - 1u;
            uvec2 a = min(child, last), b = min(child + 1u, last);
            float depth = max(max(farthest[belowOffset + a.y * below.x + a.x], farthest[belowOffset + a.y * below.x + b.x]),
                              max(farthest[belowOffset + b.y * below.x + a.x], farthest[belowOffset + b.y * below.x + b.x]));
            farthest[offset + i] = depth;
        }
        memoryBarrierBuffer();
        barrier();
    }
}
