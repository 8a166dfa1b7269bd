#version 460
#extension GL_GOOGLE_include_directive : require
// Motion blur, step 1 (seed 000 "Reconstruction filter for plausible MB [McGuire12]": tile max
// velocity): per pixel, the velocity of what it shows — a moving draw's own from the G-buffer,
// composited with the camera's, reconstructed from depth, everywhere else ("An improved
// reconstruction filter (3)": composite with camera velocity) — halved into McGuire's
// half-velocity (the image spreads that far each way from the shutter's centre) and cut to the
// longest blur radius (motionBlurMaxRadius, a quarter of the image); then the longest one of each
// k x k tile. One 16x16 workgroup per tile, each
// invocation 2x2 pixels. It also bakes |V| and the linear depth the gather weighs taps with
// ("inputs: ... bake ||V|| and depth into a R8G8 target"; RG16F here, as 8 bits of depth are too
// coarse for a soft depth test relative to the depth).
#include "common/frame_data.glsl"
#include "common/motion_blur_common.glsl"
#include "common/motion_velocity.glsl"
#include "common/view_depth.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 0, binding = 0) uniform sampler2D velocityTexture;
layout(set = 0, binding = 1) uniform sampler2D depthTexture;
layout(set = 0, binding = 2, rg16f) uniform writeonly image2D tileMax;
layout(set = 0, binding = 3, rg16f) uniform writeonly image2D speedDepth;
CAMERA_BLOCK(4);

shared vec2 longest[256];

vec2 halfVelocity(ivec2 pixel) {
    float depth = texelFetch(depthTexture, pixel, 0).r;
    vec2 v = 0.5 * pixelDisplacement(texelFetch(velocityTexture, pixel, 0).xy, depth, pixel, camera);
    float speed = length(v);
    if (speed > motionBlur.maxRadius) v *= motionBlur.maxRadius / speed;
    imageStore(speedDepth, pixel,
               vec4(min(speed, motionBlur.maxRadius), linearDepthFromDevice(camera.projection, depth), 0.0, 0.0));
    return v;
}

vec2 longer(vec2 a, vec2 b) { return dot(b, b) > dot(a, a) ? b : a; }

void main() {
    ivec2 size = ivec2(camera.resolution);
    ivec2 first = ivec2(gl_WorkGroupID.xy) * MOTION_BLUR_TILE_SIZE + 2 * ivec2(gl_LocalInvocationID.xy);
    vec2 v = vec2(0.0);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            ivec2 pixel = first + ivec2(x, y);
            if (all(lessThan(pixel, size))) v = longer(v, halfVelocity(pixel));
        }
    longest[gl_LocalInvocationIndex] = v;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (gl_LocalInvocationIndex < stride)
            longest[gl_LocalInvocationIndex] = longer(longest[gl_LocalInvocationIndex],
                                                      longest[gl_LocalInvocationIndex + stride]);
        barrier();
    }
    if (gl_LocalInvocationIndex == 0u) imageStore(tileMax, ivec2(gl_WorkGroupID.xy), vec4(longest[0], 0.0, 0.0));
}
