#version 460
#extension GL_GOOGLE_include_directive : require
// Motion blur, step 2 (seed 000 "Reconstruction filter for plausible MB [McGuire12]": tile
// neighbor max velocity): the longest tile max velocity of the 3x3 tiles around each tile. A
// pixel can be covered by anything moving at most k pixels away, so this is the direction the
// gather searches along, and zero lets a tile out early.
#include "common/motion_blur_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D tileMax;
layout(set = 0, binding = 1, rg16f) uniform writeonly image2D neighbourMax;

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(neighbourMax);
    if (any(greaterThanEqual(tile, size))) return;
    vec2 longest = vec2(0.0);
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 neighbour = clamp(tile + ivec2(x, y), ivec2(0), size - 1);
            vec2 v = texelFetch(tileMax, neighbour, 0).xy;
            if (dot(v, v) > dot(longest, longest)) longest = v;
        }
    imageStore(neighbourMax, tile, vec4(longest, 0.0, 0.0));
}
