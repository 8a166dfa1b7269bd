#version 460
#extension GL_GOOGLE_include_directive : require
// SSAO step 3: one axis of a separable bilateral blur at half resolution (seed 004 "SSAO
// improvements"). Five taps weighted 1/2 1 1 1 1/2 span exactly one period of the 4x4 sample
// pattern, so on a continuous surface the two axes together average all 16 sample rotations of a
// block (interleaved sampling, Keller & Heidrich 2001). A tap's weight falls with its depth's
// distance from the surface through the centre, extrapolated along the centre's depth slope so
// that tilted planes keep every tap, relative to the centre's depth (ssaoDepthWeight): taps across
// a depth edge drop out.
#include "common/ssao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D accessibilityTexture;
layout(set = 0, binding = 1) uniform sampler2D halfDepthTexture;
layout(set = 0, binding = 2, r8) uniform writeonly image2D blurred;

layout(push_constant) uniform Push {
    ivec2 axis;  // (1, 0) or (0, 1): the step between taps
} push;

const float kTapWeights[5] = float[](0.5, 1.0, 1.0, 1.0, 0.5);

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(blurred);
    if (any(greaterThanEqual(texel, size))) return;
    float centreDepth = texelFetch(halfDepthTexture, texel, 0).r;

    // The depth slope comes from the side that continues the surface (the smaller step); where
    // both steps are edges the surface is taken as facing the camera.
    ivec2 previous = texel - push.axis, next = texel + push.axis;
    bool hasPrevious = all(greaterThanEqual(previous, ivec2(0))), hasNext = all(lessThan(next, size));
    float before = hasPrevious ? centreDepth - texelFetch(halfDepthTexture, previous, 0).r : 0.0;
    float after = hasNext ? texelFetch(halfDepthTexture, next, 0).r - centreDepth : before;
    if (!hasPrevious) before = after;
    float slope = abs(before) < abs(after) ? before : after;
    if (ssaoDepthWeight(slope, centreDepth) == 0.0) slope = 0.0;

    float sum = 0.0, weightSum = 0.0;
    for (int i = -2; i <= 2; ++i) {
        ivec2 tap = texel + i * push.axis;
        if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
        float difference = texelFetch(halfDepthTexture, tap, 0).r - (centreDepth + float(i) * slope);
        float weight = kTapWeights[i + 2] * ssaoDepthWeight(difference, centreDepth);
        sum += weight * texelFetch(accessibilityTexture, tap, 0).r;
        weightSum += weight;
    }
    // The centre always counts fully, so weightSum >= 1.
    imageStore(blurred, texel, vec4(sum / weightSum));
}
