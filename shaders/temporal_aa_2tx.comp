#version 460
#extension GL_GOOGLE_include_directive : require
// Frame step 9, alternative mode: the SMAA 2TX temporal blend (seed 000 "Temporal SSAA \ SMAA
// 2TX/4X review"; seed 003 typesets the absolute difference of the velocity lengths): two
// sub-pixel buffers, the 2x jitter pattern, and the previous frame reprojected and blended with
//   w = 0.5 max(0, 1 - K sqrt(| |v_c| - |v_p| |)),  c = (1 - w) c_c + w c_p.
// The history keeps this frame's own colour (not the blend) and, in alpha, its velocity length.
// Velocity is the camera's motion from depth; where an object moved on its own the depth test
// rejects the history (no object velocity target yet), and a changed colour on a still surface
// is not tracked at all: the robustness flaws of seed 000 "Temporal AA \ common robustness flaws"
// that SMAA 1TX (temporal_aa.comp) addresses.
#include "common/temporal_aa_common.glsl"

layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D resolvedColor;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(historyColor);
    if (any(greaterThanEqual(pixel, size))) return;
    float deviceDepth = texelFetch(currentDepth, pixel, 0).r;
    vec3 current = texelFetch(currentColor, pixel, 0).rgb;
    storeHistoryDepth(pixel, deviceDepth);

    Reprojection r = reproject(pixel, size);
    // |v_c|: how far the pixel's surface point moved on screen since last frame, in pixels.
    float speed = length(r.position - (vec2(pixel) + 0.5));
    vec3 result = current;
    if (historyReadable() && r.valid) {
        vec4 previous = sampleHistory(r.position, size);  // rgb: last frame's colour, a: |v_p|
        float weight = 0.5 * max(0.0, 1.0 - taa.weights.z * sqrt(abs(speed - previous.a)));
        result = mix(current, previous.rgb, weight);
    }
    imageStore(historyColor, pixel, vec4(current, speed));
    imageStore(resolvedColor, pixel, vec4(result, 1.0));
}
