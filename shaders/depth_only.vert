#version 460
#extension GL_GOOGLE_include_directive : require
// Depth-only drawing (passes/depth_only_draw.cpp), vertex stage: the G-buffer's vertex layout and
// instance records, projected by a pushed view-projection — one view of the shadow atlas, or the
// camera for clip volumes. Opaque shadow casters and clip volumes run this stage alone; shadow
// casters with an opacity cut-out add shadow_cutout.frag, which reads the texture coordinates and
// the instance; sphere impostors (built with SPHERE_IMPOSTOR) its SPHERE_IMPOSTOR variant, which
// reads the world position and the corner's sphere data too (common/sphere_impostor.glsl).
#include "common/frame_data.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 3) in vec2 inSt;
#ifdef SPHERE_IMPOSTOR
layout(location = 4) in vec4 inSphere;  // a cube corner's offset from its point, and the radius
#endif

layout(set = 0, binding = 0, std430) readonly buffer Instances { InstanceData instances[]; };

#ifdef CULLED_INSTANCES
// GPU occlusion culling (shaders/occlusion_cull.comp): the records the culling pass left to the
// draw, from its list offset (instanceIndex).
layout(set = 0, binding = 2, std430) readonly buffer DrawnRecords { uint drawnRecords[]; };
#endif

layout(push_constant) uniform Push {
    mat4 viewProjection;  // world -> clip of the view being rendered
    uint instanceIndex;   // the draw's first instance record (its list offset when culled)
    // The rasteriser's slope-scaled depth bias factor, for fragment stages that write their depth
    // (which the rasteriser's bias does not reach): sphere impostors.
    float depthBiasSlope;
} push;

layout(location = 0) out vec2 outUv;
layout(location = 1) flat out uint outInstance;
#ifdef SPHERE_IMPOSTOR
layout(location = 2) out vec3 outWorldPosition;
layout(location = 3) out vec4 outSphere;  // the offset in world space, the object-space radius
#endif

void main() {
#ifdef CULLED_INSTANCES
    outInstance = drawnRecords[push.instanceIndex + uint(gl_InstanceIndex)];
#else
    outInstance = push.instanceIndex + uint(gl_InstanceIndex);
#endif
    // USD's st has its origin at the bottom left of the image, Vulkan's row 0 is the top.
    outUv = vec2(inSt.x, 1.0 - inSt.y);
    mat4 model = instances[outInstance].model;
    vec4 world = model * vec4(inPosition, 1.0);
    gl_Position = push.viewProjection * world;
#ifdef SPHERE_IMPOSTOR
    outWorldPosition = world.xyz;
    outSphere = vec4(mat3(model) * inSphere.xyz, inSphere.w);
#endif
}
