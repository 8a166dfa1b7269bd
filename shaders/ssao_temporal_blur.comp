#version 460
#extension GL_GOOGLE_include_directive : require
// SSAO step 2, in one pass: the temporal accumulation, then the bilateral blur of what it
// accumulated (seed 004 "SSAO improvements"). A workgroup accumulates its tile and the texels the
// blur reaches around it into shared memory, writing the history for its own tile alone; the blur
// then reads its taps from there. Tiles overlap by the blur's radius: 720 accumulations for 512
// texels, where a pass of its own would cost a dispatch, a barrier and a round trip through memory.
//
// Temporal accumulation with reprojection (seed 004: accumulate the noisy obscurance over frames,
// reprojecting the history with the camera's motion): each half-resolution texel finds where its
// surface point was in the previous frame's view, and takes the history there if that history's
// depth is the point's own (a disocclusion or a moved object fails the test and restarts the
// accumulation). The history is clamped to the range of this frame's 3x3 neighbourhood (the
// neighbourhood clamp of seed 000's SMAA 1TX): occlusion that left while the depth stayed, when an
// occluder is removed or moves away, does not linger. Up to `maxFrames` frames are averaged with
// equal weights; the sample pattern turns from frame to frame (ssao_obscurance.comp), so each adds
// directions the others lacked.
//
// The separable bilateral blur, both axes: the tile's rows and the two rows either side of it
// blurred horizontally into shared memory, then its columns. Five taps weighted 1/2 1 1 1 1/2 span
// exactly one period of the 4x4 sample pattern, so on a continuous surface the two axes together
// average all 16 sample rotations of a block (interleaved sampling, Keller & Heidrich 2001). A
// tap's weight falls with its depth's distance from the surface through the centre, extrapolated
// along the centre's depth slope so that tilted planes keep every tap, relative to the centre's
// depth (ssaoDepthWeight): taps across a depth edge drop out. Each stage keeps the precision of the
// image it would otherwise be stored in (the history's 16-bit float, the horizontal result's 8
// bits), so the frame is the one separate passes make.
#include "common/frame_data.glsl"
#include "common/ssao_common.glsl"

// A tall tile: the rows above and below it, accumulated and blurred horizontally by two
// workgroups, are 4 of 36.
const int TILE_WIDTH = 16, TILE_HEIGHT = 32;
const int RADIUS = 2;
const int SPAN_WIDTH = TILE_WIDTH + 2 * RADIUS, SPAN_HEIGHT = TILE_HEIGHT + 2 * RADIUS;
layout(local_size_x = TILE_WIDTH, local_size_y = TILE_HEIGHT) in;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1) uniform sampler2D currentAccessibility;
layout(set = 0, binding = 2) uniform sampler2D currentDepth;
layout(set = 0, binding = 3) uniform sampler2D currentNormal;  // a: which pixel of the 2x2 the texel holds
layout(set = 0, binding = 4) uniform sampler2D historyAccessibility;  // x accessibility, y frames / maxFrames
layout(set = 0, binding = 5) uniform sampler2D historyDepth;
layout(set = 0, binding = 6, rg16f) uniform writeonly image2D accumulated;
layout(set = 0, binding = 7, r32f) uniform writeonly image2D accumulatedDepth;
layout(set = 0, binding = 8, r8) uniform writeonly image2D blurred;

layout(push_constant) uniform Push {
    mat4 viewToPreviousView;  // this frame's view space to the previous frame's
    float maxFrames;
    uint historyValid;        // 0 on the first frame and after a reset
} push;

const float kTapWeights[5] = float[](0.5, 1.0, 1.0, 1.0, 0.5);

// The accumulated accessibility of the tile and RADIUS texels around it, as the history holds it.
shared float accumulatedSpan[SPAN_HEIGHT][SPAN_WIDTH];
// The tile's rows and RADIUS rows above and below it, blurred horizontally.
shared float horizontal[SPAN_HEIGHT][TILE_WIDTH];

// This frame's accumulated accessibility at `texel` (x) and the frames it holds / maxFrames (y).
vec2 accumulate(ivec2 texel, ivec2 size) {
    float depth = texelFetch(currentDepth, texel, 0).r;
    float current = texelFetch(currentAccessibility, texel, 0).r;
    float result = current, frames = 1.0;
    if (push.historyValid != 0u) {
        vec2 ndc = heldPixelNdc(texel, texelFetch(currentNormal, texel, 0).a, camera.resolution);
        vec4 previous = push.viewToPreviousView * vec4(viewPositionFromLinearDepth(camera.projection, ndc, depth), 1.0);
        vec4 clip = camera.projection * previous;
        ivec2 historyTexel = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * camera.resolution * 0.5));
        if (clip.w > 0.0 && all(greaterThanEqual(historyTexel, ivec2(0))) && all(lessThan(historyTexel, size))) {
            float expected = -previous.z;
            float held = texelFetch(historyDepth, historyTexel, 0).r;
            // Half the blur's tolerance: the texel must hold this very surface.
            if (ssaoDepthWeight(held - expected, expected) > 0.5) {
                vec2 history = texelFetch(historyAccessibility, historyTexel, 0).rg;
                float lowest = current, highest = current;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        float neighbour = texelFetch(currentAccessibility, clamp(texel + ivec2(dx, dy), ivec2(0), size - 1), 0).r;
                        lowest = min(lowest, neighbour);
                        highest = max(highest, neighbour);
                    }
                frames = min(round(history.y * push.maxFrames) + 1.0, push.maxFrames);
                result = mix(clamp(history.x, lowest, highest), current, 1.0 / frames);
            }
        }
    }
    return vec2(result, frames / push.maxFrames);
}

// One axis of the blur at `texel`, reading the accumulation (horizontal) or the horizontal result.
float blurAxis(ivec2 texel, ivec2 axis, ivec2 size, bool horizontalResult, ivec2 tileOrigin) {
    float centreDepth = texelFetch(currentDepth, texel, 0).r;
    // The depth slope comes from the side that continues the surface (the smaller step); where
    // both steps are edges the surface is taken as facing the camera.
    ivec2 previous = texel - axis, next = texel + axis;
    bool hasPrevious = all(greaterThanEqual(previous, ivec2(0))), hasNext = all(lessThan(next, size));
    float before = hasPrevious ? centreDepth - texelFetch(currentDepth, previous, 0).r : 0.0;
    float after = hasNext ? texelFetch(currentDepth, next, 0).r - centreDepth : before;
    if (!hasPrevious) before = after;
    float slope = abs(before) < abs(after) ? before : after;
    if (ssaoDepthWeight(slope, centreDepth) == 0.0) slope = 0.0;

    float sum = 0.0, weightSum = 0.0;
    for (int i = -RADIUS; i <= RADIUS; ++i) {
        ivec2 tap = texel + i * axis;
        if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
        float difference = texelFetch(currentDepth, tap, 0).r - (centreDepth + float(i) * slope);
        float weight = kTapWeights[i + RADIUS] * ssaoDepthWeight(difference, centreDepth);
        ivec2 local = tap - tileOrigin + ivec2(RADIUS);
        float value = horizontalResult ? horizontal[local.y][local.x - RADIUS] : accumulatedSpan[local.y][local.x];
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
    for (uint index = invocation; index < uint(SPAN_HEIGHT * SPAN_WIDTH); index += uint(TILE_WIDTH * TILE_HEIGHT)) {
        ivec2 local = ivec2(int(index) % SPAN_WIDTH, int(index) / SPAN_WIDTH);
        ivec2 texel = tileOrigin + local - ivec2(RADIUS);
        float value = 0.0;
        if (all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, size))) {
            vec2 result = accumulate(texel, size);
            if (all(greaterThanEqual(local, ivec2(RADIUS))) && all(lessThan(local, ivec2(RADIUS) + ivec2(TILE_WIDTH, TILE_HEIGHT)))) {
                imageStore(accumulated, texel, vec4(result, 0.0, 0.0));
                imageStore(accumulatedDepth, texel, vec4(texelFetch(currentDepth, texel, 0).r));
            }
            // As the RG16F history holds it.
            value = unpackHalf2x16(packHalf2x16(vec2(result.x, 0.0))).x;
        }
        accumulatedSpan[local.y][local.x] = value;
    }
    barrier();
    for (uint index = invocation; index < uint(SPAN_HEIGHT * TILE_WIDTH); index += uint(TILE_WIDTH * TILE_HEIGHT)) {
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
