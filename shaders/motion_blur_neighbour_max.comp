#version 460
#extension GL_GOOGLE_include_directive : require
// Motion blur, step 2 (seed 000 "Reconstruction filter for plausible MB [McGuire12]": tile
// neighbor max velocity): the longest tile max velocity among the tiles whose blur can reach each
// tile. This is the direction the gather searches along, and zero lets a tile out early.
// McGuire's 3x3 tiles hold every blur up to the tile side k; a longer one (a shutter has no
// maximum) reaches ceil(maxRadius / k) tiles away, so the search spans that many, and a tile
// beyond the 3x3 counts only where its blur's path meets this tile (Guertin et al. 2014 test the
// direction of the 3x3's diagonal neighbours alike): a streak lends its velocity along its own
// length, not to the tiles beside it.
#include "common/motion_blur_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D tileMax;
layout(set = 0, binding = 1, rg16f) uniform writeonly image2D neighbourMax;

// Whether a pixel of a tile `offset` pixels away (this tile's centre minus the other's) moving by
// s v, s in [-1, 1] (the half-velocity both ways from the shutter's centre), can land in this
// tile: the segment [-v, v] meets the box of half side k around `offset` (the two tiles'
// Minkowski difference). A slab test; touching counts, so the 3x3 neighbours always do.
bool reaches(vec2 v, vec2 offset) {
    float k = float(MOTION_BLUR_TILE_SIZE);
    float enter = -1.0, leave = 1.0;
    for (int axis = 0; axis < 2; ++axis) {
        float low = offset[axis] - k, high = offset[axis] + k;
        if (abs(v[axis]) < 1e-6) {
            if (low > 0.0 || high < 0.0) return false;
            continue;
        }
        float a = low / v[axis], b = high / v[axis];
        enter = max(enter, min(a, b));
        leave = min(leave, max(a, b));
    }
    return enter <= leave;
}

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(neighbourMax);
    if (any(greaterThanEqual(tile, size))) return;
    int reach = max(1, int(ceil(motionBlur.maxRadius / float(MOTION_BLUR_TILE_SIZE))));
    vec2 longest = vec2(0.0);
    for (int y = -reach; y <= reach; ++y)
        for (int x = -reach; x <= reach; ++x) {
            ivec2 neighbour = tile + ivec2(x, y);
            if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
            vec2 v = texelFetch(tileMax, neighbour, 0).xy;
            if (dot(v, v) > dot(longest, longest) && reaches(v, -vec2(x, y) * float(MOTION_BLUR_TILE_SIZE)))
                longest = v;
        }
    imageStore(neighbourMax, tile, vec4(longest, 0.0, 0.0));
}
