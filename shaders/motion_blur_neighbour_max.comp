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
// The search spans up to (2 ceil(maxRadius / k) + 1)^2 tiles (961 at 1080p), so one workgroup
// scans one tile's neighbourhood, its invocations sharing the tiles, and reduces in shared memory:
// one invocation per tile walking them all was the whole effect's slowest step.
#include "common/motion_blur_common.glsl"

#define GROUP_SIZE 64
layout(local_size_x = GROUP_SIZE) in;

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

// Each invocation's longest reaching velocity and its index in the row-major scan: the longest
// wins, and of equal ones the first scanned, as a single scan would choose.
shared vec2 longest[GROUP_SIZE];
shared float longestLength[GROUP_SIZE];
shared int longestIndex[GROUP_SIZE];

bool before(float length2, int index, uint other) {
    return length2 > longestLength[other] || (length2 == longestLength[other] && index < longestIndex[other]);
}

void main() {
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    ivec2 size = imageSize(neighbourMax);
    int reach = max(1, int(ceil(motionBlur.maxRadius / float(MOTION_BLUR_TILE_SIZE))));
    int side = 2 * reach + 1;
    vec2 best = vec2(0.0);
    float bestLength = 0.0;
    int bestIndex = side * side;
    for (int i = int(gl_LocalInvocationIndex); i < side * side; i += GROUP_SIZE) {
        ivec2 offset = ivec2(i % side, i / side) - reach;
        ivec2 neighbour = tile + offset;
        if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
        vec2 v = texelFetch(tileMax, neighbour, 0).xy;
        float length2 = dot(v, v);
        if (length2 > bestLength && reaches(v, -vec2(offset) * float(MOTION_BLUR_TILE_SIZE))) {
            best = v;
            bestLength = length2;
            bestIndex = i;
        }
    }
    uint self = gl_LocalInvocationIndex;
    longest[self] = best;
    longestLength[self] = bestLength;
    longestIndex[self] = bestIndex;
    barrier();
    for (uint stride = GROUP_SIZE / 2; stride > 0u; stride >>= 1) {
        if (self < stride && before(longestLength[self + stride], longestIndex[self + stride], self)) {
            longest[self] = longest[self + stride];
            longestLength[self] = longestLength[self + stride];
            longestIndex[self] = longestIndex[self + stride];
        }
        barrier();
    }
    if (self == 0u) imageStore(neighbourMax, tile, vec4(longest[0], 0.0, 0.0));
}
