// The display/view transform (seed 004 "Color grading"; Selan 2007, GPU Gems 3 ch. 24): exposed
// scene-linear colour through the OCIO processor baked into a 3D LUT (pass_support/color_lut.h), a
// log2 shaper mapping the HDR range onto the lattice and one trilinear lookup, clamped to the
// display range. The parameters mirror pass_support/color_lut.h's shaper.
#ifndef OBSCURA_DISPLAY_TRANSFORM_GLSL
#define OBSCURA_DISPLAY_TRANSFORM_GLSL

struct DisplayShaper {
    float minStops;
    float rangeStops;
    float middleGrey;
    float lutSize;
};

// color_lut.cpp shaperEncode: log2 stops around middle grey, with a linear toe that is the tangent
// from the origin (so 0 maps to 0 without a kink).
vec3 shaperEncode(vec3 x, DisplayShaper shaper) {
    const float ln2 = 0.69314718;
    float toeSlope = 1.0 / (shaper.rangeStops * ln2);
    float toeEnd = shaper.middleGrey * exp2(shaper.minStops + 1.0 / ln2);
    vec3 logPart = (log2(max(x, vec3(1e-30)) / shaper.middleGrey) - shaper.minStops) / shaper.rangeStops;
    vec3 toePart = x * toeSlope / toeEnd;
    return clamp(mix(logPart, toePart, lessThan(x, vec3(toeEnd))), 0.0, 1.0);
}

vec3 displayTransform(vec3 sceneLinear, sampler3D lut, DisplayShaper shaper) {
    // Lattice points sit at texel centres: scale and offset so 0 and 1 hit the first and last.
    vec3 coordinate = shaperEncode(sceneLinear, shaper) * ((shaper.lutSize - 1.0) / shaper.lutSize) + 0.5 / shaper.lutSize;
    return clamp(textureLod(lut, coordinate, 0.0).rgb, 0.0, 1.0);
}

#endif
