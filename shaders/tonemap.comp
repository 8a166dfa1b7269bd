#version 460
// Frame step 12: exposed scene-linear colour through the display/view transform baked into a 3D
// LUT (seed 004 "Color grading"; Selan 2007, GPU Gems 3 ch. 24): a log2 shaper maps the HDR range
// onto the lattice, one trilinear lookup applies the whole OCIO processor, the result is clamped
// to the display range and written as 8 bits.
#extension GL_GOOGLE_include_directive : require
#include "common/instance_target.glsl"
#include "common/coverage.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D hdrColor;  // any float format: light accumulation or TAA
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D displayColor;
layout(set = 0, binding = 2) uniform usampler2D instanceTexture;
layout(set = 0, binding = 3) uniform sampler3D gradingLut;
layout(set = 0, binding = 4) uniform sampler2D transparentCoverage;

layout(push_constant) uniform Push {
    float shaperMinStops;
    float shaperRangeStops;
    float middleGrey;
    float lutSize;
    uint alphaIsCoverage;  // passes/hdr_color.h
    float backdropCoverage;  // CameraData::backdropCoverage: a dome is seen behind everything
} push;

// pass_support/color_lut.cpp shaperEncode: log2 stops around middle grey, with a linear toe that is the
// tangent from the origin (so 0 maps to 0 without a kink).
vec3 shaperEncode(vec3 x) {
    const float ln2 = 0.69314718;
    float toeSlope = 1.0 / (push.shaperRangeStops * ln2);
    float toeEnd = push.middleGrey * exp2(push.shaperMinStops + 1.0 / ln2);
    vec3 logPart = (log2(max(x, vec3(1e-30)) / push.middleGrey) - push.shaperMinStops) / push.shaperRangeStops;
    vec3 toePart = x * toeSlope / toeEnd;
    return clamp(mix(logPart, toePart, lessThan(x, vec3(toeEnd))), 0.0, 1.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(displayColor);
    if (any(greaterThanEqual(pixel, size))) return;
    vec4 hdrSample = texelFetch(hdrColor, pixel, 0);
    vec3 hdr = hdrSample.rgb;
    // Lattice points sit at texel centres: scale and offset so 0 and 1 hit the first and last.
    vec3 coordinate = shaperEncode(hdr) * ((push.lutSize - 1.0) / push.lutSize) + 0.5 / push.lutSize;
    vec3 display = clamp(textureLod(gradingLut, coordinate, 0.0).rgb, 0.0, 1.0);
    float opaque = max(instanceIdFromTarget(texelFetch(instanceTexture, pixel, 0).r) != 0u ? 1.0 : 0.0,
                       push.backdropCoverage);
    float alpha = push.alphaIsCoverage != 0u ? hdrSample.a
                                             : compositeCoverage(opaque, texelFetch(transparentCoverage, pixel, 0).r);
    imageStore(displayColor, pixel, vec4(display, alpha));
}
