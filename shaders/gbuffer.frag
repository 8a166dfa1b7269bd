#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, fragment stage of static geometry (common/gbuffer_surface.glsl): it leaves the
// velocity target, where there is one, at its clear value: the camera's motion, from depth.
#include "common/gbuffer_surface.glsl"

void main() { writeSurface(); }
