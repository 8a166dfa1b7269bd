#version 460
#extension GL_GOOGLE_include_directive : require
// Frame step 9 while the scene and the camera stay unchanged (passes/temporal_aa.cpp): the history
// holds an equal-weight mean of the n frames since the last change and this frame adds its own with
// weight 1 / (n + 1), up to taa:frames. The jitter sequence then covers the pixel and a still
// converges to the box-filtered supersampled image, which the slide's exponential weights (seed 000
// "SMAA 1TX", temporal_aa.comp) never reach: they forever favour the latest few jitter offsets.
// Nothing moves, so there is nothing to reproject and nothing to clamp away (the clamp would only
// bias sub-pixel features). The first frame after a change has n = 0: the blend the change left
// is no jittered sample, and its 1/n share would cost a converged edge a few dB.
#include "common/temporal_aa_common.glsl"

layout(set = 0, binding = 7, r32f) uniform writeonly image2D historyDepth;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(historyColor);
    if (any(greaterThanEqual(pixel, size))) return;
    float deviceDepth = texelFetch(currentDepth, pixel, 0).r;
    imageStore(historyDepth, pixel, vec4(linearDepthFromDevice(camera.projection, deviceDepth)));
    uint heldFrames = taa.frames.y, framesToConverge = taa.frames.z;
    vec4 history = texelFetch(previousColor, pixel, 0);
    // A converged still keeps its mean.
    vec4 result = heldFrames >= framesToConverge
                      ? history
                      : mix(currentSample(pixel, deviceDepth), history, float(heldFrames) / float(heldFrames + 1u));
    imageStore(historyColor, pixel, result);
}
