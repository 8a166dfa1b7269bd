// Screen-space velocities for motion blur: the displacement in pixels (x right, y down) of a
// surface point from the shutter's open to its close.
#ifndef OBSCURA_MOTION_VELOCITY_GLSL
#define OBSCURA_MOTION_VELOCITY_GLSL

#include "frame_data.glsl"

// The G-buffer velocity target's clear value (passes/gbuffer.h kStaticVelocity): no moving draw
// covered the pixel, its velocity is the camera's, reconstructed from depth.
const float STATIC_VELOCITY = -65504.0;
// Longer displacements (a vertex crossing the eye plane within the shutter) are cut to this.
const float MAX_DISPLACEMENT = 16384.0;

vec2 shutterDisplacement(vec4 openClip, vec4 closeClip, vec2 resolution) {
    // A point behind the eye at either end has no image there: keep the clip w positive, which
    // sends it far off screen, and bound the result.
    vec2 open = openClip.xy / max(openClip.w, 1e-6);
    vec2 close = closeClip.xy / max(closeClip.w, 1e-6);
    vec2 d = 0.5 * (close - open) * resolution;
    float len = length(d);
    return len > MAX_DISPLACEMENT ? d * (MAX_DISPLACEMENT / len) : d;
}

// The displacement of what `pixel` shows: a moving draw's own (`stored`, from the G-buffer's
// velocity target) or, where that holds STATIC_VELOCITY, the camera's, reconstructed from the
// pixel's device depth (seed 000 "An improved reconstruction filter (3)": composite with camera
// velocity).
vec2 pixelDisplacement(vec2 stored, float depth, ivec2 pixel, CameraData camera) {
    if (stored.x != STATIC_VELOCITY) return stored;
    vec2 ndc = (vec2(pixel) + 0.5) / camera.resolution * 2.0 - 1.0;
    vec4 world = camera.inverseViewProjection * vec4(ndc, depth, 1.0);
    world /= world.w;
    return shutterDisplacement(camera.shutterOpenViewProjection * world, camera.shutterCloseViewProjection * world,
                               camera.resolution);
}

#endif
