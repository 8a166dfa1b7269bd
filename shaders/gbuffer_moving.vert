#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, vertex stage of rigid geometry whose transform moves within the shutter.
#include "common/gbuffer_motion_vertex.glsl"

void main() {
    gl_Position = cameraClip(surfaceVertex(inPosition));
    writeShutterClips(inPosition, inPosition);
}
