#version 460
#extension GL_GOOGLE_include_directive : require
// SSAO step 3: temporal accumulation with reprojection (seed 004 "SSAO improvements": accumulate
// the noisy obscurance over frames, reprojecting the history with the camera's motion). Each
// half-resolution texel finds where its surface point was in the previous frame's view, and takes
// the history there if that history's depth is the point's own (a disocclusion or a moved object
// fails the test and restarts the accumulation). The history is clamped to the range of this
// frame's 3x3 neighbourhood (the neighbourhood clamp of seed 000's SMAA 1TX): occlusion that left
// while the depth stayed, when an occluder is removed or moves away, does not linger. Up to
// `maxFrames` frames are averaged with equal weights; the sample pattern turns from frame to frame
// (ssao_obscurance.comp), so each adds directions the others lacked.
#include "common/frame_data.glsl"
#include "common/ssao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1) uniform sampler2D currentAccessibility;
layout(set = 0, binding = 2) uniform sampler2D currentDepth;
layout(set = 0, binding = 3) uniform sampler2D currentNormal;  // a: which pixel of the 2x2 the texel holds
layout(set = 0, binding = 4) uniform sampler2D historyAccessibility;  // x accessibility, y frames / maxFrames
layout(set = 0, binding = 5) uniform sampler2D historyDepth;
layout(set = 0, binding = 6, rg16f) uniform writeonly image2D accumulated;
layout(set = 0, binding = 7, r32f) uniform writeonly image2D accumulatedDepth;

layout(push_constant) uniform Push {
    mat4 viewToPreviousView;  // this frame's view space to the previous frame's
    float maxFrames;
    uint historyValid;        // 0 on the first frame and after a reset
} push;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(accumulated);
    if (any(greaterThanEqual(texel, size))) return;
    float depth = texelFetch(currentDepth, texel, 0).r;
    float current = texelFetch(currentAccessibility, texel, 0).r;
    imageStore(accumulatedDepth, texel, vec4(depth));

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
    imageStore(accumulated, texel, vec4(result, frames / push.maxFrames, 0.0, 0.0));
}
