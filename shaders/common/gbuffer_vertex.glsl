// G-buffer pass, vertex stage shared by the static and the moving draws: world transform from the
// instance buffer, the surface attributes the fragment stage reads.
#ifndef OBSCURA_GBUFFER_VERTEX_GLSL
#define OBSCURA_GBUFFER_VERTEX_GLSL

#include "frame_data.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inColor;  // displayColor, displayOpacity
layout(location = 3) in vec2 inSt;
layout(location = 4) in vec4 inTangent;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };

layout(push_constant) uniform Push { uint instanceIndex; } push;
#ifdef CULLED_INSTANCES
// GPU occlusion culling (shaders/occlusion_cull.comp): the records the culling pass left to the
// draw, from the draw's list offset (the push constant).
layout(set = 0, binding = 5, std430) readonly buffer DrawnRecords { uint drawnRecords[]; };
#endif

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec4 outColor;
layout(location = 2) out vec3 outWorldPosition;
layout(location = 3) flat out uint outInstance;
layout(location = 4) out vec2 outUv;
layout(location = 5) out vec4 outTangent;

// Writes the surface outputs for the vertex at `position` (object space) and returns its world
// position.
vec4 surfaceVertex(vec3 position) {
#ifdef CULLED_INSTANCES
    outInstance = drawnRecords[push.instanceIndex + uint(gl_InstanceIndex)];
#else
    // One record per GPU instance, consecutive from the draw's first record.
    outInstance = push.instanceIndex + uint(gl_InstanceIndex);
#endif
    InstanceData inst = instances[outInstance];
    vec4 world = inst.model * vec4(position, 1.0);
    outWorldPosition = world.xyz;
    outNormal = mat3(inst.normalMatrix) * inNormal;
    outColor = inColor;
    // Tangents follow the surface like positions (the model's linear part), unlike normals.
    outTangent = vec4(mat3(inst.model) * inTangent.xyz, inTangent.w);
    // USD's st has its origin at the bottom left of the image, Vulkan's row 0 is the top.
    outUv = vec2(inSt.x, 1.0 - inSt.y);
    return world;
}

// The world position through the frame's camera: jittered for temporal AA, except instances that
// hybrid AA gives to edge AA (seed 004 "Hybrid anti-aliasing": "separate it with stencil and
// non-jittered camera"), which stay on the pixel grid. Call after surfaceVertex().
vec4 cameraClip(vec4 world) {
    vec4 clip = camera.viewProjection * world;
    if ((instances[outInstance].flags & INSTANCE_EDGE_AA) != 0u) clip.xy -= camera.clipJitter * clip.w;
    return clip;
}

#endif
