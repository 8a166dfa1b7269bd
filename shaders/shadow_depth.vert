#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow maps, vertex stage (the only stage: depth only). The G-buffer's vertex layout and
// instance records, projected into one view of the shadow atlas.
#include "common/frame_data.glsl"

layout(location = 0) in vec3 inPosition;

layout(set = 0, binding = 0, std430) readonly buffer Instances { InstanceData instances[]; };

layout(push_constant) uniform Push {
    mat4 viewProjection;  // world -> clip of the atlas view being rendered
    uint instanceIndex;   // the draw's first instance record
} push;

void main() {
    InstanceData inst = instances[push.instanceIndex + uint(gl_InstanceIndex)];
    gl_Position = push.viewProjection * (inst.model * vec4(inPosition, 1.0));
}
