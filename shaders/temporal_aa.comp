#version 460
#extension GL_GOOGLE_include_directive : require
// Frame step 9: SMAA 1TX (seed 000 "SMAA 1TX: a more robust temporal AA"): an accumulation
// buffer, reprojected, its colour clamped to the extent of the current frame's neighbourhood and
// blended with weights for high and low frequencies:
//   c_max = max(c_TL, c_TR, c_BL, c_BR), c_min = min(...), c_acc = clamp(c_acc, c_min, c_max)
//   w_k = |(c_TL + c_TR + c_BL + c_BR) * 0.25 - c_M|
//   w_rgb = clamp(1 / (K_lowfreq (1 - w_k) + K_hifreq w_k), 0, 1)
//   c = c_M (1 - w_rgb) + c_acc w_rgb
// (slides "SMAA 1TX (2)" and "(3)"; seed 003 typesets the same). It tracks the signal, not the
// geometry, so lights, materials and transparents that change do not ghost.
// While the scene and the camera stay unchanged, the history holds an equal-weight mean of the
// frames since and each frame adds its own with weight 1 / (n + 1), up to taa:frames: the jitter
// sequence then covers the pixel and a still converges to the box-filtered supersampled image
// (the slide's exponential weights would forever favour the latest few jitter offsets). Nothing
// moves, so there is nothing to reproject or clamp: the clamp would only bias sub-pixel features.
#include "common/temporal_aa_common.glsl"

// The slide's cross: the four diagonal neighbours, and the pixel itself, so that a feature thinner
// than the cross's reach (a one-pixel line) keeps its accumulated colour where this frame's sample
// hit it, rather than being clamped to its background.
struct Neighbourhood {
    vec3 minimum;
    vec3 maximum;
    vec3 highFrequency;  // w_k
};

Neighbourhood crossNeighbourhood(ivec2 pixel, ivec2 size, vec3 centre) {
    vec3 tl = texelFetch(currentColor, clamp(pixel + ivec2(-1, -1), ivec2(0), size - 1), 0).rgb;
    vec3 tr = texelFetch(currentColor, clamp(pixel + ivec2(1, -1), ivec2(0), size - 1), 0).rgb;
    vec3 bl = texelFetch(currentColor, clamp(pixel + ivec2(-1, 1), ivec2(0), size - 1), 0).rgb;
    vec3 br = texelFetch(currentColor, clamp(pixel + ivec2(1, 1), ivec2(0), size - 1), 0).rgb;
    Neighbourhood n;
    n.minimum = min(min(min(tl, tr), min(bl, br)), centre);
    n.maximum = max(max(max(tl, tr), max(bl, br)), centre);
    n.highFrequency = abs((tl + tr + bl + br) * 0.25 - centre);
    return n;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(historyColor);
    if (any(greaterThanEqual(pixel, size))) return;
    float deviceDepth = texelFetch(currentDepth, pixel, 0).r;
    vec3 current = texelFetch(currentColor, pixel, 0).rgb;
    storeHistoryDepth(pixel, deviceDepth);

    vec3 result = current;
    uint heldFrames = taa.frames.y, framesToConverge = taa.frames.z;
    if (historyReadable() && heldFrames > 0u) {
        // An unchanged scene: the running mean, which stops at taa:frames (a converged still).
        float historyWeight = heldFrames >= framesToConverge ? 1.0 : float(heldFrames) / float(heldFrames + 1u);
        result = mix(current, texelFetch(previousColor, pixel, 0).rgb, historyWeight);
    } else if (historyReadable()) {
        Reprojection r = reproject(pixel, size);
        if (r.valid) {
            Neighbourhood n = crossNeighbourhood(pixel, size, current);
            vec3 accumulated = clamp(sampleHistory(r.position, size).rgb, n.minimum, n.maximum);
            // w_k is a difference of pre-exposed radiance, display-referred near 1 like the
            // slide's; clamped so that an HDR edge does not extrapolate past K_hifreq.
            vec3 k = mix(vec3(taa.weights.x), vec3(taa.weights.y), clamp(n.highFrequency, 0.0, 1.0));
            vec3 historyWeight = clamp(1.0 / k, 0.0, 1.0);
            result = mix(current, accumulated, historyWeight);
        }
    }
    imageStore(historyColor, pixel, vec4(result, 1.0));
}
