#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 4 (seed 000 "Final composite"): the fields over the sharp full-resolution
// image.
// * Far field: upscaled with a bilateral filter, four bicubic-weighted taps [Sigg05] each
//   weighted again by how close the field's CoC there is to this pixel's CoC, so a blurred
//   background never smears over a sharp edge; blended by this pixel's far CoC.
// * Near field: upscaled "carelessly" with the same bicubic taps, free to bleed over whatever
//   lies behind, blended by its own coverage (its CoC-derived alpha).
// * Full-resolution fields (a still's samples) are read with one bilinear tap instead, where the
//   jitter puts the pixel's content: a B-spline would blur the edges of a cell's bokeh by more
//   than the pixel's own box does.
// * Blending is non-linear (fieldBlend, against the "hat of shame" of linear blending).
// * Under the near field, a near pixel's own sharp colour gives way to an estimate of what it hides
//   (the seed's near field leaves it; its light is in the near field already).
// Tiles where nothing is blurred copy the sharp image (dynamic branching on the tile CoC).
#include "common/dof_common.glsl"
#include "common/bicubic.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D lightAccumulation;
layout(set = 0, binding = 1) uniform sampler2D depthTexture;
layout(set = 0, binding = 2) uniform sampler2D nearField;
layout(set = 0, binding = 3) uniform sampler2D farField;
layout(set = 0, binding = 4) uniform sampler2D fieldCoc;
layout(set = 0, binding = 5) uniform sampler2D neighbourhoodCoc;
// The light accumulation's format, whichever it is (lighting:halfFloat): written without one.
layout(set = 0, binding = 6) uniform writeonly image2D outputColor;

// Weight of a field texel's far CoC against the pixel's: 1 when equal, falling to 0 at a
// difference of half the pixel's CoC (relative, so it reads the same at every blur size), and at
// least one texel wide.
float farCocWeight(float fieldCocRadius, float pixelCoc) {
    return max(1.0 - abs(fieldCocRadius - pixelCoc) / max(0.5 * pixelCoc, 1.0), 0.0);
}

// What a near pixel hides. Its own light is in the near field already (scattered over its CoC),
// so what shows through where that field is thin is the scene behind it, which one layer of
// colour does not hold; the sharp pixels where its blur ends, in eight directions, stand in for
// it, those not in the near field themselves. None: deep inside a near object, where the near
// field covers all. (Blurring the far ones among them as well was measured to make no difference.)
vec3 hiddenBehindNearPixel(ivec2 pixel, float nearRadius) {
    ivec2 lastPixel = imageSize(outputColor) - 1;
    vec3 sum = vec3(0.0);
    float count = 0.0;
    const float d = 0.70710678;
    const vec2 directions[8] = vec2[](vec2(1, 0), vec2(d, d), vec2(0, 1), vec2(-d, d), vec2(-1, 0), vec2(-d, -d),
                                      vec2(0, -1), vec2(d, -d));
    for (int i = 0; i < 8; ++i) {
        ivec2 neighbour = clamp(pixel + ivec2(round(nearRadius * directions[i])), ivec2(0), lastPixel);
        if (nearFieldShare(signedCocRadius(texelFetch(depthTexture, neighbour, 0).r)) > 0.0) continue;
        sum += texelFetch(lightAccumulation, neighbour, 0).rgb;
        count += 1.0;
    }
    return count > 0.0 ? sum / count : vec3(0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(outputColor)))) return;
    // Alpha passes through: a still's sample (addTemporalAaSamplePass) keeps its coverage for the
    // mean. XXX: the coverage itself is not blurred.
    vec4 sharpTexel = texelFetch(lightAccumulation, pixel, 0);
    vec3 sharp = sharpTexel.rgb;
    float maxRadius = fieldMaxRadius();
    vec2 tile = texelFetch(neighbourhoodCoc, (pixel / int(dof.pixelsPerTexel)) / DOF_TILE_SIZE, 0).xy * maxRadius;
    if (!blursInField(tile.x) && !blursInField(tile.y)) {
        imageStore(outputColor, pixel, sharpTexel);
        return;
    }
    vec2 fieldSize = vec2(textureSize(nearField, 0));
    // The fields read where this pixel's content lies unshifted by the frame's jitter.
    vec2 position = (vec2(pixel) + 0.5 + dof.jitter) / dof.pixelsPerTexel;
    BicubicTaps taps = bicubicBSplineTaps(position, fieldSize);
    if (dof.pixelsPerTexel == 1.0) taps = BicubicTaps(vec2[](position / fieldSize, vec2(0.0), vec2(0.0), vec2(0.0)),
                                                      float[](1.0, 0.0, 0.0, 0.0));

    vec3 colour = sharp;
    float coc = signedCocRadius(texelFetch(depthTexture, pixel, 0).r);
    float farRadius = max(-coc, 0.0);
    float farBlend = fieldBlend(farRadius);
    if (farBlend > 0.0) {
        vec4 bilateral = vec4(0.0), plain = vec4(0.0);
        for (int i = 0; i < 4; ++i) {
            vec4 field = textureLod(farField, taps.uv[i], 0.0);
            float coc = textureLod(fieldCoc, taps.uv[i], 0.0).y * maxRadius;
            bilateral += taps.weight[i] * farCocWeight(coc, farRadius / dof.pixelsPerTexel) * field;
            plain += taps.weight[i] * field;
        }
        // Where no tap's CoC matches (a lone pixel), the plain bicubic answer.
        vec4 far = bilateral.a > 1e-4 ? bilateral : plain;
        if (far.a > 1e-4) colour = mix(sharp, far.rgb / far.a, farBlend);
    }
    if (blursInField(tile.x)) {
        vec4 near = vec4(0.0);
        for (int i = 0; i < 4; ++i) near += taps.weight[i] * textureLod(nearField, taps.uv[i], 0.0);
        float nearSelf = nearFieldShare(coc);
        if (nearSelf > 0.0) colour = mix(colour, hiddenBehindNearPixel(pixel, coc * dof.cellShare), nearSelf);
        colour = colour * (1.0 - near.a) + near.rgb;
    }
    imageStore(outputColor, pixel, vec4(colour, sharpTexel.a));
}
