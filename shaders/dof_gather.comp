#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 4: the first pass of the separable flexible filter (seed 000 "A plausible
// and efficient DOF reconstruction filter"), tapsPerSide^2 taps (7x7) of a square kernel mapped to
// the aperture ("Sampling"), at half resolution, near and far fields in the same pass with dynamic
// branching on the tile CoC ("Tile min/max CoC"). The taps are built once per workgroup.
//
// Far field ("scale kernel size and weight samples with far CoC" [Scheuermann05]): the kernel is
// the texel's own far CoC; a sample counts where its own blur reaches this texel, weighted by its
// CoC (the layer is premultiplied by it [Gotanda09]). The result stays premultiplied: rgb / a is
// the colour, a the mean weight.
//
// Near field (scatter as gather): the kernel is the tile neighbourhood's largest near CoC R; a
// sample of near CoC r reaching this texel stands for (R / r)^2 of its disc, as if it scattered
// its colour over its own circle, so alpha is the fraction of this texel the near field covers
// (cheap partial occlusion); sharp samples do not spread. Premultiplied: rgb = colour * alpha.
//
// Orientation: gathering at p + o shows each sample's blur as the aperture reflected through its
// centre. The near field's bokeh is that (a real lens inverts it); the far field gathers at p - o
// so that its bokeh is upright, as behind a real lens.
#include "common/dof_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D nearLayer;
layout(set = 0, binding = 1) uniform sampler2D farLayer;
layout(set = 0, binding = 2) uniform sampler2D halfCoc;
layout(set = 0, binding = 3) uniform sampler2D neighbourhoodCoc;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D nearField;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D farField;

const int MAX_TAPS = 15 * 15;  // passes/depth_of_field.h kMaxDofTapsPerSide
shared vec3 taps[MAX_TAPS];

void main() {
    int tapCount = dof.tapsPerSide * dof.tapsPerSide;
    for (int i = int(gl_LocalInvocationIndex); i < tapCount; i += 64) taps[i] = apertureTap(squareGridCell(i, dof.tapsPerSide));
    barrier();

    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(nearField);
    if (any(greaterThanEqual(texel, size))) return;
    vec2 inverseSize = 1.0 / vec2(size);
    vec2 centre = vec2(texel) + 0.5;
    float maxRadius = halfResolutionMaxRadius();
    float sharpRadius = 0.5 * DOF_SHARP_RADIUS;
    vec2 tile = texelFetch(neighbourhoodCoc, texel / DOF_TILE_SIZE, 0).xy * maxRadius;
    vec2 coc = texelFetch(halfCoc, texel, 0).xy * maxRadius;

    vec4 far = vec4(texelFetch(farLayer, texel, 0).rgb, coc.y / maxRadius);
    if (coc.y > sharpRadius) {
        vec4 sum = vec4(0.0);
        float area = 0.0;
        for (int i = 0; i < tapCount; ++i) {
            vec2 offset = taps[i].xy * coc.y;
            vec2 uv = (centre - apertureToTexels(offset)) * inverseSize;
            float fraction = textureLod(halfCoc, uv, 0.0).y;
            float reach = clamp(fraction * maxRadius - length(offset) + 0.5, 0.0, 1.0);
            sum += taps[i].z * reach * vec4(textureLod(farLayer, uv, 0.0).rgb, fraction);
            area += taps[i].z;
        }
        far = sum / area;
    }

    vec4 near = vec4(0.0);
    if (tile.x > sharpRadius) {
        float area = 0.0;
        for (int i = 0; i < tapCount; ++i) {
            vec2 offset = taps[i].xy * tile.x;
            vec2 uv = (centre + apertureToTexels(offset)) * inverseSize;
            float fraction = textureLod(halfCoc, uv, 0.0).x;
            float radius = fraction * maxRadius;
            area += taps[i].z;
            float isNear = fieldBlend(2.0 * radius);
            if (isNear == 0.0) continue;
            float reach = clamp(radius - length(offset) + 0.5, 0.0, 1.0);
            float spread = tile.x / radius;
            float weight = taps[i].z * isNear * reach * spread * spread;
            near += weight * vec4(textureLod(nearLayer, uv, 0.0).rgb / fraction, 1.0);
        }
        near /= area;
        if (near.a > 0.0) {
            // Overlapping spreads saturate; a near texel is covered by its own field as far as
            // it belongs to it (the non-linear blend of dof_composite).
            float coverage = max(min(near.a, 1.0), fieldBlend(2.0 * coc.x));
            near = vec4(near.rgb / near.a * coverage, coverage);
        }
    }
    imageStore(nearField, texel, near);
    imageStore(farField, texel, far);
}
