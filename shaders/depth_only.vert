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

#ifdef CULLED_INSTANCES
// GPU occlusion culling (shaders/occlusion_cull.comp): the records the culling pass left to the
// draw, from its list offset (instanceIndex).
layout(set = 0, binding = 2, std430) readonly buffer DrawnRecords { uint drawnRecords[]; };
#endif

layout(push_constant) uniform Push {
    mat4 viewProjection;  // world -> clip of the view being rendered
    uint instanceIndex;   // the draw's first instance record (its list offset when culled)
} push;

layout(location = 0) out vec2 outUv;
layout(location = 1) flat out uint outInstance;

void main() {
#ifdef CULLED_INSTANCES
    outInstance = drawnRecords[push.instanceIndex + uint(gl_InstanceIndex)];
#else
    outInstance = push.instanceIndex + uint(gl_InstanceIndex);
#endif
    // USD's st has its origin at the bottom left of the image, Vulkan's row 0 is the top.
    outUv = vec2(inSt.x, 1.0 - inSt.y);
    gl_Position = push.viewProjection * (instances[outInstance].model * vec4(inPosition, 1.0));
}
