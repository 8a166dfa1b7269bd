#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 4: the first pass of the separable flexible filter (seed 000 "A plausible
// and efficient DOF reconstruction filter"), tapsPerSide^2 taps (7x7) of a square kernel mapped to
// the aperture ("Sampling"), at half resolution, near and far fields in the same pass ("Tile
// min/max CoC"), each branching out where it has nothing to blur: the near field on its tile
// neighbourhood's CoC, the far field on the texel's own. The taps are built once per workgroup.
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
        float kernel = kernelRadius(coc.y);
        for (int i = 0; i < tapCount; ++i) {
            vec2 offset = taps[i].xy * kernel;
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
        // Each tap stands for a ring of the kernel as wide as the rings are apart (2R/N): a sample
        // reaching partway into that ring counts partly, so a coverage of whole rings does not
        // round the disc of a smaller CoC down.
        float kernel = kernelRadius(tile.x);
        float ringWidth = max(2.0 * kernel / float(dof.tapsPerSide), 1.0);
        float area = 0.0;
        for (int i = 0; i < tapCount; ++i) {
            vec2 offset = taps[i].xy * kernel;
            vec2 position = centre + apertureToTexels(offset);
            area += taps[i].z;
            // The spread depends on the CoC non-linearly, so it comes from the texel under the tap;
            // the bilinear fetches give the colour and how much of the footprint is near field.
            float nearest = texelFetch(halfCoc, clamp(ivec2(floor(position)), ivec2(0), size - 1), 0).x;
            float radius = nearest * maxRadius;
            float isNear = fieldBlend(2.0 * radius);
            if (isNear == 0.0) continue;
            vec2 uv = position * inverseSize;
            float fraction = textureLod(halfCoc, uv, 0.0).x;
            float coverage = min(fraction / nearest, 1.0);
            float reach = clamp((radius - length(offset)) / ringWidth + 0.5, 0.0, 1.0);
            float spread = tile.x / radius;
            float weight = taps[i].z * isNear * reach * spread * spread * coverage;
            near += weight * vec4(textureLod(nearLayer, uv, 0.0).rgb / fraction, 1.0);
        }
        near /= area;
        // Where spreads overlap the field is opaque: coverage saturates, the colour keeps its mix.
        if (near.a > 1.0) near /= near.a;
    }
    imageStore(nearField, texel, near);
    imageStore(farField, texel, far);
}
