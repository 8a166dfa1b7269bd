#version 460
#extension GL_GOOGLE_include_directive : require
// SSAO step 4: the separable bilateral blur at half resolution (seed 004 "SSAO improvements"),
// both axes in one pass: a workgroup blurs its tile's rows and the two rows either side of it
// into shared memory, then its columns. Five taps weighted 1/2 1 1 1 1/2 span exactly one period of
// the 4x4 sample pattern, so on a continuous surface the two axes together average all 16 sample
// rotations of a block (interleaved sampling, Keller & Heidrich 2001). A tap's weight falls with
// its depth's distance from the surface through the centre, extrapolated along the centre's depth
// slope so that tilted planes keep every tap, relative to the centre's depth (ssaoDepthWeight):
// taps across a depth edge drop out. The horizontal result is kept at the 8 bits of the result's
// format, as a separate pass would store it.
#include "common/ssao_common.glsl"

// A tall tile: the rows above and below it, blurred horizontally by two workgroups, are 4 of 36.
const int TILE_WIDTH = 16, TILE_HEIGHT = 32;
const int RADIUS = 2;
layout(local_size_x = TILE_WIDTH, local_size_y = TILE_HEIGHT) in;

layout(set = 0, binding = 0) uniform sampler2D signalTexture;
layout(set = 0, binding = 1) uniform sampler2D halfDepthTexture;
layout(set = 0, binding = 2, r8) uniform writeonly image2D blurred;

const float kTapWeights[5] = float[](0.5, 1.0, 1.0, 1.0, 0.5);

// The tile's rows and RADIUS rows above and below it, blurred horizontally.
shared float horizontal[TILE_HEIGHT + 2 * RADIUS][TILE_WIDTH];

// One axis of the blur at `texel`, reading `signal` (the input, or the horizontal result).
float blurAxis(ivec2 texel, ivec2 axis, ivec2 size, bool fromShared, ivec2 tileOrigin) {
    float centreDepth = texelFetch(halfDepthTexture, texel, 0).r;
    // The depth slope comes from the side that continues the surface (the smaller step); where
    // both steps are edges the surface is taken as facing the camera.
    ivec2 previous = texel - axis, next = texel + axis;
    bool hasPrevious = all(greaterThanEqual(previous, ivec2(0))), hasNext = all(lessThan(next, size));
    float before = hasPrevious ? centreDepth - texelFetch(halfDepthTexture, previous, 0).r : 0.0;
    float after = hasNext ? texelFetch(halfDepthTexture, next, 0).r - centreDepth : before;
    if (!hasPrevious) before = after;
    float slope = abs(before) < abs(after) ? before : after;
    if (ssaoDepthWeight(slope, centreDepth) == 0.0) slope = 0.0;

    float sum = 0.0, weightSum = 0.0;
    for (int i = -RADIUS; i <= RADIUS; ++i) {
        ivec2 tap = texel + i * axis;
        if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
        float difference = texelFetch(halfDepthTexture, tap, 0).r - (centreDepth + float(i) * slope);
        float weight = kTapWeights[i + RADIUS] * ssaoDepthWeight(difference, centreDepth);
        ivec2 local = tap - tileOrigin + ivec2(0, RADIUS);
        float value = fromShared ? horizontal[local.y][local.x] : texelFetch(signalTexture, tap, 0).r;
        sum += weight * value;
        weightSum += weight;
    }
    // The centre always counts fully, so weightSum >= 1.
    return sum / weightSum;
}

void main() {
    ivec2 size = imageSize(blurred);
    ivec2 tileOrigin = ivec2(gl_WorkGroupID.xy) * ivec2(TILE_WIDTH, TILE_HEIGHT);
    uint invocation = gl_LocalInvocationIndex;
    for (uint index = invocation; index < uint((TILE_HEIGHT + 2 * RADIUS) * TILE_WIDTH);
         index += uint(TILE_WIDTH * TILE_HEIGHT)) {
        ivec2 local = ivec2(int(index) % TILE_WIDTH, int(index) / TILE_WIDTH);
        ivec2 texel = tileOrigin + ivec2(local.x, local.y - RADIUS);
        float value = 0.0;
        if (all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, size))) {
            // As an r8 image would hold it: rounded to the nearest of 256 levels (ties to even), read
            // back as level / 255 (the unorm conversion's multiply).
            float horizontalBlur = blurAxis(texel, ivec2(1, 0), size, false, tileOrigin);
            value = roundEven(clamp(horizontalBlur, 0.0, 1.0) * 255.0) * (1.0 / 255.0);
        }
        horizontal[local.y][local.x] = value;
    }
    barrier();
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, size))) return;
    imageStore(blurred, texel, vec4(blurAxis(texel, ivec2(0, 1), size, true, tileOrigin)));
}
