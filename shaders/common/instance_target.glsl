// The G-buffer's R32_UINT instance target (passes/gbuffer.h): the low 24 bits hold the instance
// record's index + 1 (0: nothing drawn), the high 8 bits the material's `occlusion`
// (UsdPreviewSurface), the one per-pixel input that has no other room in the thin G-buffer
// (seed 004 "G-Buffer layout": normal + roughness and albedo + metallic fill RT0 and RT1).
// Every reader of the target goes through these functions.
#ifndef OBSCURA_INSTANCE_TARGET_GLSL
#define OBSCURA_INSTANCE_TARGET_GLSL

const uint INSTANCE_ID_BITS = 24u;
const uint INSTANCE_ID_MASK = (1u << INSTANCE_ID_BITS) - 1u;

uint packInstanceTarget(uint instanceIndex, float occlusion) {
    uint occlusionCode = uint(round(clamp(occlusion, 0.0, 1.0) * 255.0));
    return ((instanceIndex + 1u) & INSTANCE_ID_MASK) | (occlusionCode << INSTANCE_ID_BITS);
}

// The instance record's index + 1; 0 where nothing was drawn.
uint instanceIdFromTarget(uint target) { return target & INSTANCE_ID_MASK; }

float occlusionFromTarget(uint target) { return float(target >> INSTANCE_ID_BITS) / 255.0; }

#endif
