#version 460
#extension GL_GOOGLE_include_directive : require
// AOV readback (frame steps 12 and 13): converts one frame resource into the host's render buffer layout
// (Hydra's AOV conventions, see include/obscura/obscura.h). The display AOV is the HDR colour
// through the display/view transform, applied here: tone mapping is folded into the frame's last
// pass (one read of the HDR colour, one write, no display image between).
#extension GL_EXT_scalar_block_layout : require
#include "common/frame_data.glsl"
#include "common/best_fit_normals.glsl"
#include "common/motion_velocity.glsl"
#include "common/instance_target.glsl"
#include "common/coverage.glsl"
#include "common/display_transform.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

const uint AOV_COLOR = 0u;
const uint AOV_DEPTH = 1u;
const uint AOV_NORMAL = 2u;
const uint AOV_ALBEDO = 3u;
const uint AOV_PRIM_ID = 4u;
const uint AOV_DISPLAY = 5u;
const uint AOV_MOTION = 6u;
const uint AOV_INSTANCE_ID = 7u;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2) uniform sampler2D depthTexture;
layout(set = 0, binding = 3) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 4) uniform sampler2D albedoMetallicTexture;
layout(set = 0, binding = 5) uniform usampler2D instanceTexture;
layout(set = 0, binding = 6) uniform sampler2D hdrColor;  // any float format: light accumulation or TAA
layout(set = 0, binding = 7) uniform sampler3D displayLut;  // pass_support/color_grading_lut.h
layout(set = 0, binding = 8, scalar) writeonly buffer Floats { float floats[]; };
layout(set = 0, binding = 9, scalar) writeonly buffer Words { uint words[]; };
layout(set = 0, binding = 10) uniform sampler2D transparentCoverage;  // passes/transparent.h
// The G-buffer's velocity target, or one STATIC_VELOCITY texel where the frame has none.
layout(set = 0, binding = 11) uniform sampler2D velocityTexture;

layout(push_constant) uniform Push {
    uint aov;
    uint width;
    uint height;
    uint alphaIsCoverage;  // passes/hdr_color.h
    DisplayShaper shaper;
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height)) return;
    uint index = uint(pixel.y) * push.width + uint(pixel.x);
    // Read by the AOVs that need it only: the colour's alpha comes from the colour itself where it
    // holds coverage (temporal AA's), and the display AOV of such a frame reads nothing else.
    bool colour = push.aov == AOV_COLOR || push.aov == AOV_DISPLAY;
    bool needsInstance = colour ? push.alphaIsCoverage == 0u : push.aov != AOV_DEPTH && push.aov != AOV_MOTION;
    uint instanceId = needsInstance ? instanceIdFromTarget(texelFetch(instanceTexture, pixel, 0).r) : 0u;
    bool covered = instanceId != 0u;
    if (colour) {
        vec4 hdr = texelFetch(hdrColor, pixel, 0);
        hdr.rgb *= camera.outputScale;
        // Premultiplied alpha: the opaque coverage with the transparent surfaces' over it.
        float a = push.alphaIsCoverage != 0u
                      ? hdr.a
                      : compositeCoverage(max(covered ? 1.0 : 0.0, camera.backdropCoverage),
                                          transparentCoverageAt(transparentCoverage, pixel));
        if (push.aov == AOV_DISPLAY) {
            words[index] = packUnorm4x8(vec4(displayTransform(hdr.rgb, displayLut, push.shaper), a));
        } else {
            for (uint i = 0u; i < 3u; ++i) floats[index * 4u + i] = hdr[i];
            floats[index * 4u + 3u] = a;
        }
    } else if (push.aov == AOV_DEPTH) {
        floats[index] = texelFetch(depthTexture, pixel, 0).r;
    } else if (push.aov == AOV_NORMAL) {
        vec3 n = covered ? normalize(mat3(camera.view) * decodeBestFitNormal(texelFetch(normalRoughnessTexture, pixel, 0).xyz))
                         : vec3(0.0);
        for (uint i = 0u; i < 3u; ++i) floats[index * 3u + i] = n[i];
    } else if (push.aov == AOV_ALBEDO) {
        vec3 a = covered ? texelFetch(albedoMetallicTexture, pixel, 0).rgb : vec3(0.0);
        for (uint i = 0u; i < 3u; ++i) floats[index * 3u + i] = a[i];
    } else if (push.aov == AOV_PRIM_ID) {
        words[index] = uint(covered ? instances[instanceId - 1u].primId : -1);
    } else if (push.aov == AOV_INSTANCE_ID) {
        words[index] = uint(covered ? instances[instanceId - 1u].instanceId : -1);
    } else if (push.aov == AOV_MOTION) {
        vec2 stored = texelFetch(velocityTexture, min(pixel, textureSize(velocityTexture, 0) - 1), 0).xy;
        // The whole shutter's displacement, also in a still's sample whose velocities span one
        // stratum of it (at the stratum's rate).
        vec2 d = pixelDisplacement(stored, texelFetch(depthTexture, pixel, 0).r, pixel, camera) / camera.shutterFraction;
        floats[index * 3u] = d.x;
        floats[index * 3u + 1u] = d.y;
        floats[index * 3u + 2u] = 0.0;
    }
}
