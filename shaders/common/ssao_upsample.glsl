// The lighting pass's read of the half-resolution SSAO (passes/ssao.h): a depth-aware (bilateral)
// 2x2 upsample. Bilinear weights, each scaled by how well the texel's depth matches the pixel's, so
// occlusion never bleeds across a silhouette; where no texel of the four matches, the one of the
// closest depth answers (nearest-depth upsampling).
#ifndef OBSCURA_SSAO_UPSAMPLE_GLSL
#define OBSCURA_SSAO_UPSAMPLE_GLSL

#include "common/ssao_common.glsl"

// accessibility and halfDepth: SsaoResult's images; pixel: the full-resolution pixel; linearDepth:
// its distance along the view axis, linearDepthFromDevice(camera.projection, G-buffer depth).
// Returns the ambient accessibility, 1 = unoccluded.
float sampleAmbientAccess(sampler2D accessibility, sampler2D halfDepth, ivec2 pixel, float linearDepth) {
    ivec2 lastTexel = textureSize(halfDepth, 0) - 1;
    // Texel t's centre lies at full-resolution coordinate 2t + 1, so pixel centres fall a quarter
    // or three quarters of the way between four texel centres.
    vec2 position = (vec2(pixel) + 0.5) * 0.5 - 0.5;
    ivec2 base = ivec2(floor(position));
    vec2 f = position - vec2(base);
    float sum = 0.0, weightSum = 0.0;
    float closest = 1.0, closestDifference = 1e30;
    for (int i = 0; i < 4; ++i) {
        ivec2 offset = ivec2(i & 1, i >> 1);
        ivec2 texel = clamp(base + offset, ivec2(0), lastTexel);
        vec2 bilinear = mix(1.0 - f, f, vec2(offset));
        float difference = abs(texelFetch(halfDepth, texel, 0).r - linearDepth);
        float value = texelFetch(accessibility, texel, 0).r;
        float weight = bilinear.x * bilinear.y * ssaoDepthWeight(difference, linearDepth);
        sum += weight * value;
        weightSum += weight;
        if (difference < closestDifference) {
            closestDifference = difference;
            closest = value;
        }
    }
    return weightSum > 0.0 ? sum / weightSum : closest;
}

#endif
