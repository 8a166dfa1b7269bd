#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 3: the first pass of the separable flexible filter (seed 000 "A plausible
// and efficient DOF reconstruction filter"), tapsPerSide^2 taps (7x7) of a square kernel mapped to
// the aperture ("Sampling"), in the field texels, near and far fields in the same pass ("Tile
// min/max CoC"), each branching out where it has nothing to blur: the near field on its tile
// neighbourhood's CoC, the far field on the texel's own. The taps are built once per workgroup.
//
// The taps span the frame's cell of the aperture (the whole of it in a real-time frame; a still's
// sample its own cell, dof_common.glsl cellTap), spread evenly (the mapping preserves area).
//
// Far field ("scale kernel size and weight samples with far CoC" [Scheuermann05]): the kernel is
// the texel's own far CoC; a sample counts where its own blur reaches this texel (its CoC times
// the cell's reach along the tap), weighted by its CoC (the layer is premultiplied by it
// [Gotanda09]). The result stays premultiplied: rgb / a is
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
layout(set = 0, binding = 2) uniform sampler2D fieldCoc;
layout(set = 0, binding = 3) uniform sampler2D neighbourhoodCoc;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D nearField;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D farField;

const int MAX_TAPS = 15 * 15;  // passes/depth_of_field.h kMaxDofTapsPerSide
shared vec3 taps[MAX_TAPS];

void main() {
    int tapCount = dof.tapsPerSide * dof.tapsPerSide;
    for (int i = int(gl_LocalInvocationIndex); i < tapCount; i += 64) taps[i] = cellTap(squareGridCell(i, dof.tapsPerSide));
    barrier();

    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(nearField);
    if (any(greaterThanEqual(texel, size))) return;
    vec2 inverseSize = 1.0 / vec2(size);
    vec2 centre = vec2(texel) + 0.5;
    float maxRadius = fieldMaxRadius();
    vec2 tile = texelFetch(neighbourhoodCoc, texel / DOF_TILE_SIZE, 0).xy * maxRadius;
    vec2 coc = texelFetch(fieldCoc, texel, 0).xy * maxRadius;

    vec4 far = vec4(texelFetch(farLayer, texel, 0).rgb, coc.y / maxRadius);
    if (blursInField(coc.y)) {
        vec4 sum = vec4(0.0);
        float kernel = kernelRadius(coc.y);
        for (int i = 0; i < tapCount; ++i) {
            vec2 offset = taps[i].xy * kernel;
            vec2 uv = (centre - apertureToTexels(offset)) * inverseSize;
            vec4 cocAndShares = textureLod(fieldCoc, uv, 0.0);
            float fraction = cocAndShares.y;
            if (fraction <= 0.0) continue;
            float radius = fraction * maxRadius;
            float reach = tapReach(radius, taps[i].z, length(offset));
            float spread = min(coc.y / radius, DOF_MAX_SPREAD);
            sum += reach * spread * spread * cocAndShares.w * vec4(textureLod(farLayer, uv, 0.0).rgb / fraction, 1.0);
        }
        far = sum / float(tapCount);
    }

    vec4 near = vec4(0.0);
    if (blursInField(tile.x)) {
        float kernel = kernelRadius(tile.x);
        for (int i = 0; i < tapCount; ++i) {
            vec2 offset = taps[i].xy * kernel;
            vec2 position = centre + apertureToTexels(offset);
            // The four texels around the tap, each whole with its bilinear weight (a tent that holds
            // exactly the light of its texel): its CoC (the spread depends on it non-linearly), its
            // colour and the share of its pixels in the near field.
            vec2 corner = position - 0.5;
            ivec2 base = ivec2(floor(corner));
            vec2 f = corner - vec2(base);
            for (int k = 0; k < 4; ++k) {
                ivec2 t = ivec2(k & 1, k >> 1);
                float bilinear = (t.x == 1 ? f.x : 1.0 - f.x) * (t.y == 1 ? f.y : 1.0 - f.y);
                ivec2 under = clamp(base + t, ivec2(0), size - 1);
                vec4 cocAndShares = texelFetch(fieldCoc, under, 0);
                float radius = cocAndShares.x * maxRadius;
                float isNear = nearFieldShare(2.0 * radius);
                if (isNear * bilinear == 0.0) continue;
                float reach = tapReach(radius, taps[i].z, length(offset));
                float spread = tile.x / radius;
                float weight = bilinear * isNear * reach * spread * spread * cocAndShares.z;
                near += weight * vec4(texelFetch(nearLayer, under, 0).rgb / cocAndShares.x, 1.0);
            }
        }
        near /= float(tapCount);
        // Where spreads overlap the field is opaque: coverage saturates, the colour keeps its mix.
        if (near.a > 1.0) near /= near.a;
    }
    imageStore(nearField, texel, near);
    imageStore(farField, texel, far);
}
