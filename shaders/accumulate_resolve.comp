#version 460
// Reference mode: the weighted mean of the sub-frames (passes/accumulate.h; alpha holds the sum of
// the weights), in the light accumulation's format for tone mapping and readback.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D accumulation;
// The light accumulation's format, whichever it is (lighting:halfFloat): written without one.
layout(set = 0, binding = 1) uniform writeonly image2D resolved;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(resolved)))) return;
    vec4 sum = imageLoad(accumulation, pixel);
    imageStore(resolved, pixel, vec4(sum.a > 0.0 ? sum.rgb / sum.a : vec3(0.0), 0.0));
}
