#version 460
#extension GL_GOOGLE_include_directive : require
// Frame step 9, alternative mode: the SMAA 2TX temporal blend (seed 000 "Temporal SSAA / SMAA
// 2TX/4X review"; seed 003 typesets the absolute difference of the velocity lengths): two
// sub-pixel buffers, the 2x jitter pattern, and the previous frame reprojected and blended with
//   w = 0.5 max(0, 1 - K sqrt(| |v_c| - |v_p| |)),  c = (1 - w) c_c + w c_p.
// The history keeps this frame's own colour (not the blend), and beside its depth the velocity
// length. Velocity is the camera's motion from depth; where an object moved on its own the depth
// test rejects the history (no object velocity target yet), and a changed colour on a still
// surface is not tracked at all: the robustness flaws of seed 000 "Temporal AA / common robustness
// flaws" that SMAA 1TX (temporal_aa.comp) addresses.
#include "common/temporal_aa_common.glsl"

layout(set = 0, binding = 7, rg32f) uniform writeonly image2D historyDepth;  // linear depth, |v|
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D resolvedColor;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(historyColor);
    loadCrossTile(size, false);
    if (any(greaterThanEqual(pixel, size))) return;
    CrossDepths depths = crossDepths();
    vec4 current = currentSample(pixel, depths.depth[0]);
    Reprojection r = reproject(pixel, size, depths);
    // |v_c|: how far the pixel's surface point moved on screen since last frame, in pixels.
    float speed = length(r.position - (vec2(pixel) + 0.5));
    vec4 result = current;
    if (historyReadable() && r.valid) {
        vec4 previous = sampleHistory(r.position, size);
        float previousSpeed = texelFetch(previousDepth, ivec2(floor(r.position)), 0).g;
        float weight = 0.5 * max(0.0, 1.0 - taa.weights.z * sqrt(abs(speed - previousSpeed)));
        // No clamp in 2TX: only Catmull-Rom's overshoot past what radiance and coverage can be.
        result = mix(current, clamp(previous, vec4(0.0), vec4(vec3(3.4e38), 1.0)), weight);
    }
    imageStore(historyColor, pixel, current);
    imageStore(historyDepth, pixel, vec4(linearDepthFromDevice(camera.projection, depths.depth[0]), speed, 0.0, 0.0));
    imageStore(resolvedColor, pixel, result);
}
