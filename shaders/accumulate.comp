#version 460
// Reference mode: adds one sub-frame's light accumulation, weighted, to the running sum (passes/
// accumulate.h). The first sub-frame starts the sum; a sub-frame's guard band is left out.
layout(local_size_x = 8, local_size_y = 8) in;

// Sampled, so that either light accumulation format reads (storage reads need a declared format).
layout(set = 0, binding = 0) uniform sampler2D hdrColor;
layout(set = 0, binding = 1, rgba32f) uniform image2D accumulation;

layout(push_constant) uniform Push {
    float weight;
    uint first;
    uint guardPixels;
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(accumulation)))) return;
    vec4 sum = push.first != 0u ? vec4(0.0) : imageLoad(accumulation, pixel);
    imageStore(accumulation, pixel, sum + push.weight * vec4(texelFetch(hdrColor, pixel + ivec2(push.guardPixels), 0).rgb, 1.0));
}
