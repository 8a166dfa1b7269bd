#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 2: the first pass of the separable flexible filter (seed 000 "A plausible
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
//
// A workgroup is one tile, and first finds the tile's neighbourhood (seed 000 "Tile min/max CoC":
// "also used for scatter as gather approximation for near field"): a near CoC spreads its blur up
// to its radius beyond its own tile, so the tile's near-field kernel is the largest near CoC of
// every tile within reach (dof.tileNeighbourhood tiles each side), read by all the invocations
// and reduced in shared memory; the far field gathers with each texel's own CoC and keeps its
// tile's own value. The composite reads the neighbourhood too: one texel per workgroup.
#include "common/dof_common.glsl"

#define GROUP_SIZE (DOF_TILE_SIZE * DOF_TILE_SIZE)
layout(local_size_x = DOF_TILE_SIZE, local_size_y = DOF_TILE_SIZE) in;

layout(set = 0, binding = 0) uniform sampler2D nearLayer;
layout(set = 0, binding = 1) uniform sampler2D farLayer;
layout(set = 0, binding = 2) uniform sampler2D fieldCoc;
layout(set = 0, binding = 3) uniform sampler2D tileCoc;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D nearField;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D farField;
layout(set = 0, binding = 6, rg8) uniform writeonly image2D neighbourhoodCoc;

const int MAX_TAPS = 15 * 15;  // passes/depth_of_field.h kMaxDofTapsPerSide
shared vec3 taps[MAX_TAPS];
shared uint neighbourhoodNearMax;  // dof_common.glsl orderedBits

// The largest near CoC fraction of the tiles within reach of this workgroup's tile, every
// invocation reading its share of them; in uniform control flow (it waits for the whole group).
float neighbourhoodNear(ivec2 tile) {
    ivec2 tiles = textureSize(tileCoc, 0);
    int side = 2 * dof.tileNeighbourhood + 1;
    float nearMax = 0.0;
    for (int i = int(gl_LocalInvocationIndex); i < side * side; i += GROUP_SIZE) {
        ivec2 neighbour = tile + ivec2(i % side, i / side) - dof.tileNeighbourhood;
        if (all(greaterThanEqual(neighbour, ivec2(0))) && all(lessThan(neighbour, tiles)))
            nearMax = max(nearMax, texelFetch(tileCoc, neighbour, 0).x);
    }
    atomicMax(neighbourhoodNearMax, orderedBits(nearMax));
    barrier();
    return uintBitsToFloat(neighbourhoodNearMax);
}

void main() {
    int tapCount = dof.tapsPerSide * dof.tapsPerSide;
    for (int i = int(gl_LocalInvocationIndex); i < tapCount; i += GROUP_SIZE) taps[i] = cellTap(squareGridCell(i, dof.tapsPerSide));
    if (gl_LocalInvocationIndex == 0) neighbourhoodNearMax = 0u;
    barrier();
    ivec2 tileIndex = ivec2(gl_WorkGroupID.xy);
    vec2 tileFractions = vec2(neighbourhoodNear(tileIndex), texelFetch(tileCoc, tileIndex, 0).y);
    if (gl_LocalInvocationIndex == 0) imageStore(neighbourhoodCoc, tileIndex, vec4(tileFractions, 0.0, 0.0));

    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(nearField);
    if (any(greaterThanEqual(texel, size))) return;
    vec2 inverseSize = 1.0 / vec2(size);
    vec2 centre = vec2(texel) + 0.5;
    float maxRadius = fieldMaxRadius();
    vec2 tile = tileFractions * maxRadius;
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
