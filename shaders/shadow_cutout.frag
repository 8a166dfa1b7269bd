#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow maps, fragment stage of draws whose material has an opacity cut-out
// (UsdPreviewSurface opacityThreshold): texels the G-buffer discards cast no shadow either. Built
// with SPHERE_IMPOSTOR for sphere impostors (common/sphere_impostor.glsl), whose cube casts the
// shadow of its sphere: the depth of the sphere seen from the light, written here.
#include "common/frame_data.glsl"
#include "common/material_inputs.glsl"
#ifdef SPHERE_IMPOSTOR
#include "common/sphere_impostor.glsl"
#endif

layout(location = 0) in vec2 inUv;
layout(location = 1) flat in uint inInstance;
#ifdef SPHERE_IMPOSTOR
// The sphere lies behind the cube face that answers (common/gbuffer_surface.glsl says the same).
layout(depth_greater) out float gl_FragDepth;
layout(location = 2) in vec3 inWorldPosition;
layout(location = 3) in vec4 inSphere;

// Mirrors depth_only.vert's.
layout(push_constant) uniform Push {
    mat4 viewProjection;
    uint instanceIndex;
    float depthBiasSlope;
} push;
#endif

layout(set = 0, binding = 0, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 1, std430) readonly buffer Materials { MaterialData materials[]; };
// The draw's opacity texture, pushed per draw (white where opacity is constant).
layout(set = 1, binding = 0) uniform sampler2D opacityTexture;

void main() {
    InstanceData inst = instances[inInstance];
#ifdef SPHERE_IMPOSTOR
    vec3 dx = dFdx(inWorldPosition), dy = dFdy(inWorldPosition);  // while the whole quad runs
    ImpostorHit sphere = impostorHit(push.viewProjection, inst.normalMatrix, inWorldPosition, inSphere);
    // The slope-scaled bias the rasteriser gives the other casters (passes/shadow_maps.cpp), from
    // the slope of the sphere's tangent plane at the hit: where the lines through the neighbouring
    // texels (the cube's point moved by its screen derivatives, exact on its plane) meet it. It
    // grows towards the rim as a grazing polygon's does.
    if (!sphere.hit) discard;
    gl_FragDepth = sphere.depth + push.depthBiasSlope * tangentPlaneDepthSlope(push.viewProjection, sphere,
                                                                                inWorldPosition, dx, dy);
#endif
    if (cutOut(materials[inst.materialIndex], opacityTexture, inUv)) discard;
}
