#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, vertex stage of deforming geometry: its points at the shutter's open and close
// come as a second vertex stream (passes::ShutterPositions); the frame sees it where it is at
// camera.shutterPosition between them (the points interpolate linearly in between, as USD's do):
// the centre of the part of the shutter a motion-blurred frame covers, the sub-frame's time in the
// reference. Its velocity spans that part (camera.shutterFraction of the shutter) alone.
#include "common/gbuffer_motion_vertex.glsl"

layout(location = 6) in vec3 inShutterOpenPosition;
layout(location = 7) in vec3 inShutterClosePosition;

void main() {
    gl_Position = cameraClip(surfaceVertex(mix(inShutterOpenPosition, inShutterClosePosition, camera.shutterPosition)));
    float halfSpan = 0.5 * camera.shutterFraction;
    writeShutterClips(mix(inShutterOpenPosition, inShutterClosePosition, camera.shutterPosition - halfSpan),
                      mix(inShutterOpenPosition, inShutterClosePosition, camera.shutterPosition + halfSpan));
}
