#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow maps, fragment stage of draws whose material has an opacity cut-out
// (UsdPreviewSurface opacityThreshold): texels the G-buffer discards cast no shadow either.
#include "common/frame_data.glsl"
#include "common/material_inputs.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 1) flat in uint inInstance;

layout(set = 0, binding = 0, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 1, std430) readonly buffer Materials { MaterialData materials[]; };
// The draw's opacity texture, pushed per draw (white where opacity is constant).
layout(set = 1, binding = 0) uniform sampler2D opacityTexture;

void main() {
    if (cutOut(materials[instances[inInstance].materialIndex], opacityTexture, inUv)) discard;
}
