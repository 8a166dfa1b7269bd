// G-buffer pass, vertex stage of geometry that moves within the shutter (seed 000 "An improved
// reconstruction filter (3)": object velocity in the G-buffer only where required): where the
// vertex is in clip space at the shutter's open and close, for the fragment's velocity
// (gbuffer_moving.frag).
#ifndef OBSCURA_GBUFFER_MOTION_VERTEX_GLSL
#define OBSCURA_GBUFFER_MOTION_VERTEX_GLSL

#include "gbuffer_vertex.glsl"

layout(set = 0, binding = 5, std430) readonly buffer Motions { InstanceMotion motions[]; };

layout(location = 6) out vec4 outShutterOpenClip;
layout(location = 7) out vec4 outShutterCloseClip;

// After surfaceVertex(): the object-space position at each end of the shutter.
void writeShutterClips(vec3 openPosition, vec3 closePosition) {
    InstanceMotion motion = motions[instances[outInstance].motionIndex];
    outShutterOpenClip = camera.shutterOpenViewProjection * (motion.shutterOpenModel * vec4(openPosition, 1.0));
    outShutterCloseClip = camera.shutterCloseViewProjection * (motion.shutterCloseModel * vec4(closePosition, 1.0));
}

#endif
