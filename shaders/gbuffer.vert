#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, vertex stage of static geometry.
#include "common/gbuffer_vertex.glsl"

void main() { gl_Position = cameraClip(surfaceVertex(inPosition)); }
