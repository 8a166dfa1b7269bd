#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, fragment stage of geometry that moves within the shutter: the surface, and its
// screen-space velocity (camera and object motion together) into RT3.
#include "common/gbuffer_surface.glsl"
#include "common/motion_velocity.glsl"

layout(location = 6) in vec4 inShutterOpenClip;
layout(location = 7) in vec4 inShutterCloseClip;

layout(location = 3) out vec2 outVelocity;

void main() {
    writeSurface();
    outVelocity = shutterDisplacement(inShutterOpenClip, inShutterCloseClip, camera.resolution);
}
