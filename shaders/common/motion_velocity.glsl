// Screen-space velocities for motion blur: the displacement in pixels (x right, y down) of a
// surface point from the shutter's open to its close.
#ifndef OBSCURA_MOTION_VELOCITY_GLSL
#define OBSCURA_MOTION_VELOCITY_GLSL

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

#endif
