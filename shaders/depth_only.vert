#version 460
#extension GL_GOOGLE_include_directive : require
// Depth-only drawing (passes/depth_only_draw.cpp), vertex stage: the G-buffer's vertex layout and
// instance records, projected by a pushed view-projection — one view of the shadow atlas, or the
// camera for clip volumes. Opaque shadow casters and clip volumes run this stage alone; shadow
// casters with an opacity cut-out add shadow_cutout.frag, which reads the texture coordinates and
// the instance.
#include "common/frame_data.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 3) in vec2 inSt;

layout(set = 0, binding = 0, std430) readonly buffer Instances { InstanceData instances[]; };

layout(push_constant) uniform Push {
    mat4 viewProjection;  // world -> clip of the view being rendered
    uint instanceIndex;   // the draw's first instance record
} push;

layout(location = 0) out vec2 outUv;
layout(location = 1) flat out uint outInstance;

void main() {
    outInstance = push.instanceIndex + uint(gl_InstanceIndex);
    // USD's st has its origin at the bottom left of the image, Vulkan's row 0 is the top.
    outUv = vec2(inSt.x, 1.0 - inSt.y);
    gl_Position = push.viewProjection * (instances[outInstance].model * vec4(inPosition, 1.0));
}
