#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 3: the second pass of the separable flexible filter (seed 000 "Sampling:
// 2nd iteration"): 3x3 taps of the same aperture shape fill the gaps between the first pass's taps.
// The first pass's taps sit 2/N of the kernel apart (the centres of an N x N grid over the square
// before the aperture mapping); these lie a third of that apart (the 3x3 cell centres at 2/3
// scaled by 1 / N, through the cell's mapping), so that the two passes together sample the kernel
// at the centres of a 3N x 3N grid, and are averaged: the light a point spreads is kept (the
// seed's boolean union, a per-channel max after McIntosh et al. 2012, kept each of the N^2 copies
// of a bright point at full strength, brightening its bokeh by up to 2.5x). Each field keeps its
// first pass's kernel radius and orientation.
#include "common/dof_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D nearGathered;
layout(set = 0, binding = 1) uniform sampler2D farGathered;
layout(set = 0, binding = 2) uniform sampler2D fieldCoc;
layout(set = 0, binding = 3) uniform sampler2D neighbourhoodCoc;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D nearField;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D farField;

const int FILL_TAPS_PER_SIDE = 3;
shared vec2 taps[FILL_TAPS_PER_SIDE * FILL_TAPS_PER_SIDE];

// Mean over the 3x3 aperture taps around `centre`, offsets scaled by `scale` texels and mirrored
// by `direction` (+1 near, -1 far, as in dof_gather).
vec4 meanOfTaps(sampler2D field, vec2 centre, vec2 inverseSize, float scale, float direction) {
    vec4 combined = vec4(0.0);
    for (int i = 0; i < FILL_TAPS_PER_SIDE * FILL_TAPS_PER_SIDE; ++i)
        combined += textureLod(field, (centre + direction * apertureToTexels(taps[i] * scale)) * inverseSize, 0.0);
    return combined / float(FILL_TAPS_PER_SIDE * FILL_TAPS_PER_SIDE);
}

void main() {
    if (gl_LocalInvocationIndex < uint(FILL_TAPS_PER_SIDE * FILL_TAPS_PER_SIDE))
        taps[gl_LocalInvocationIndex] =
            cellTap(squareGridCell(int(gl_LocalInvocationIndex), FILL_TAPS_PER_SIDE) * (1.0 / float(dof.tapsPerSide))).xy;
    barrier();

    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(nearField);
    if (any(greaterThanEqual(texel, size))) return;
    vec2 inverseSize = 1.0 / vec2(size);
    vec2 centre = vec2(texel) + 0.5;
    float maxRadius = fieldMaxRadius();
    float farRadius = texelFetch(fieldCoc, texel, 0).y * maxRadius;
    float nearRadius = texelFetch(neighbourhoodCoc, texel / DOF_TILE_SIZE, 0).x * maxRadius;

    vec4 far = blursInField(farRadius)
                   ? meanOfTaps(farGathered, centre, inverseSize, kernelRadius(farRadius), -1.0)
                   : texelFetch(farGathered, texel, 0);
    vec4 near = blursInField(nearRadius)
                    ? meanOfTaps(nearGathered, centre, inverseSize, kernelRadius(nearRadius), 1.0)
                    : texelFetch(nearGathered, texel, 0);
    imageStore(nearField, texel, near);
    imageStore(farField, texel, far);
}
