#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 1 (seed 000 "Far + near field processing", "Tile min/max CoC"): each field
// texel takes its pixels' (2x2 at half resolution, one at full) colour and circle of confusion (one
// multiply-add on depth, "Lens review (2)") and splits them into the two fields. The downscale is bilateral, not bilinear ("careful:
// downscale is source of error"): each field averages only the pixels that belong to it, weighted
// by their CoC, so a sharp pixel never leaks into a blurred field. The far field's CoC is that
// weighted mean; the near field takes the largest near CoC (its blur only grows outwards). Each
// field is stored premultiplied by its CoC [Gotanda09], so that bilinear fetches of colour and CoC
// in the gather stay consistent and sharp texels weigh nothing.
//
// A workgroup is one tile (DOF_TILE_SIZE^2 texels), so the tile's CoC comes from the same pass,
// reduced in shared memory rather than read back by a pass of its own: with the signed CoC (near
// positive, far negative) the far field takes the tile's min fragment and the near field its max;
// stored as magnitudes: x the largest near CoC, y the largest far CoC, as fractions of the largest
// radius (R8G8).
#include "common/dof_common.glsl"

layout(local_size_x = DOF_TILE_SIZE, local_size_y = DOF_TILE_SIZE) in;

layout(set = 0, binding = 0) uniform sampler2D lightAccumulation;
layout(set = 0, binding = 1) uniform sampler2D depthTexture;
// R11G11B10F, or RGBA16F in the frames of an integral (passes/depth_of_field.cpp): written without a format.
layout(set = 0, binding = 2) uniform writeonly image2D nearLayer;
layout(set = 0, binding = 3) uniform writeonly image2D farLayer;
// Near and far CoC (fractions of the largest), and each field's share of the texel's pixels.
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D fieldCoc;
layout(set = 0, binding = 5, rg8) uniform writeonly image2D tileCoc;

shared uint tileNearMax, tileFarMax;  // dof_common.glsl orderedBits

// The R8G8 value a CoC radius (full-resolution pixels) is stored as, so that the premultiplied
// colour uses exactly the CoC the gather will read back.
float quantisedCocFraction(float radius) { return round(clamp(radius / dof.maxRadius, 0.0, 1.0) * 255.0) / 255.0; }

// The field texel's near and far CoC fractions (what fieldCoc holds); written where it lies in the
// field.
vec2 downsample(ivec2 texel) {
    // Odd sizes: the last texel's missing pixels repeat the image's edge.
    ivec2 lastPixel = textureSize(depthTexture, 0) - 1;
    const int side = int(dof.pixelsPerTexel), pixels = side * side;
    vec3 mean = vec3(0.0), nearSum = vec3(0.0), farSum = vec3(0.0);
    float nearWeight = 0.0, farWeight = 0.0, farCocSum = 0.0, nearMax = 0.0;
    for (int i = 0; i < pixels; ++i) {
        ivec2 pixel = min(texel * side + ivec2(i % side, i / side), lastPixel);
        vec3 colour = texelFetch(lightAccumulation, pixel, 0).rgb;
        float coc = signedCocRadius(texelFetch(depthTexture, pixel, 0).r);
        float near = max(coc, 0.0), far = max(-coc, 0.0);
        mean += colour / float(pixels);
        nearSum += near * colour;
        nearWeight += near;
        nearMax = max(nearMax, near);
        farSum += far * colour;
        farWeight += far;
        farCocSum += far * far;
    }
    float nearFraction = quantisedCocFraction(nearMax);
    float farFraction = quantisedCocFraction(farWeight > 0.0 ? farCocSum / farWeight : 0.0);
    vec3 nearColour = nearWeight > 0.0 ? nearSum / nearWeight : mean;
    vec3 farColour = farWeight > 0.0 ? farSum / farWeight : mean;
    imageStore(nearLayer, texel, vec4(nearColour * nearFraction, 0.0));
    imageStore(farLayer, texel, vec4(farColour * farFraction, 0.0));
    // Each field's share of the texel: its pixels weighted by their CoC against the field's, so that
    // a point smaller than the texel spreads only its own light.
    float nearShare = nearMax > 0.0 ? nearWeight / (float(pixels) * nearMax) : 0.0;
    float farCoc = farWeight > 0.0 ? farCocSum / farWeight : 0.0;
    float farShare = farCoc > 0.0 ? farWeight / (float(pixels) * farCoc) : 0.0;
    imageStore(fieldCoc, texel, vec4(nearFraction, farFraction, nearShare, farShare));
    return vec2(nearFraction, farFraction);
}

void main() {
    if (gl_LocalInvocationIndex == 0) {
        tileNearMax = 0u;
        tileFarMax = 0u;
    }
    barrier();
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    // Texels beyond the field's edge (its last tiles' spare invocations) add nothing to the tile.
    if (all(lessThan(texel, imageSize(fieldCoc)))) {
        vec2 fractions = downsample(texel);
        atomicMax(tileNearMax, orderedBits(fractions.x));
        atomicMax(tileFarMax, orderedBits(fractions.y));
    }
    barrier();
    if (gl_LocalInvocationIndex == 0)
        imageStore(tileCoc, ivec2(gl_WorkGroupID.xy), vec4(uintBitsToFloat(tileNearMax), uintBitsToFloat(tileFarMax), 0.0, 0.0));
}
