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
// geometry, so lights, materials and transparents that change do not ghost. This runs in frames
// where something changed; while nothing does, temporal_aa_still.comp averages the jittered frames.
#include "common/temporal_aa_common.glsl"

layout(set = 0, binding = 7, r32f) uniform writeonly image2D historyDepth;

// The clamp's extent and the slide's w_k over the cross. The pixel itself joins the extent, so
// that a feature thinner than the cross's reach (a one-pixel line) keeps its accumulated colour
// where this frame's sample hit it, rather than being clamped to its background.
struct Neighbourhood {
    vec4 minimum;
    vec4 maximum;
    vec4 highFrequency;  // w_k
};

Neighbourhood crossNeighbourhood(vec4 centre, CrossDepths depths) {
    Neighbourhood n = Neighbourhood(centre, centre, vec4(0.0));
    vec4 sum = vec4(0.0);
    for (int i = 1; i < CROSS_TAPS; ++i) {
        vec4 c = depths.edgeAa[i] ? centre : crossColour(i);
        n.minimum = min(n.minimum, c);
        n.maximum = max(n.maximum, c);
        sum += c;
    }
    n.highFrequency = abs(sum * 0.25 - centre);
    return n;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(historyColor);
    loadCrossTile(size, true);
    if (any(greaterThanEqual(pixel, size))) return;
    CrossDepths depths = crossDepths();
    vec4 current = crossColour(0);
    imageStore(historyDepth, pixel, vec4(linearDepthFromDevice(camera.projection, depths.depth[0])));

    vec4 result = current;
    if (historyReadable() && !depths.edgeAa[0]) {
        Reprojection r = reproject(pixel, size, depths);
        if (r.valid) {
            Neighbourhood n = crossNeighbourhood(current, depths);
            vec4 accumulated = clamp(sampleHistory(r.position, size), n.minimum, n.maximum);
            // w_k is a difference of pre-exposed radiance, display-referred near 1 like the
            // slide's; clamped so that an HDR edge does not extrapolate past K_hifreq.
            vec4 k = mix(vec4(taa.weights.x), vec4(taa.weights.y), clamp(n.highFrequency, 0.0, 1.0));
            result = mix(current, accumulated, clamp(1.0 / k, 0.0, 1.0));
        }
    }
    imageStore(historyColor, pixel, result);
}
