#version 460
#extension GL_GOOGLE_include_directive : require
// Motion blur, steps 3 and 4 (seed 000 "An improved reconstruction filter"): McGuire et al.
// 2012's reconstruction filter, made separable in two passes [Sousa08]. Each pass gathers N taps
// along the tile's neighbour max velocity: the first over one step of the second (a prefilter
// along the blur), the second over the whole [-|vN|, |vN|] reading the first's result, so the two
// together place N^2 taps. Each tap is weighed against the centre with the slide's vectorised
// weights (DepthCmp, VelCmp): in front and moving over the centre (cone of the tap's velocity),
// behind and seen through the centre's own blur (cone of the centre's velocity), or both blurred
// along (the product of the two cylinders, twice).
#include "common/motion_blur_common.glsl"
#include "common/interleaved_gradient_noise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Taps read whole pixels, as McGuire's (a filtered read would mix a still pixel's neighbours
// into it wherever a tap lands within a pixel of the centre).
// Colour with coverage in alpha (temporal AA's accumulation) blurs its alpha along: a streak over
// nothing is partly transparent, as the premultiplied colour says. (B10G11R11 reads alpha 1.)
layout(set = 0, binding = 0) uniform sampler2D colorTexture;
layout(set = 0, binding = 1) uniform sampler2D speedDepth;     // |V| (pixels), linear depth
layout(set = 0, binding = 2) uniform sampler2D neighbourMax;
layout(set = 0, binding = 3) uniform writeonly image2D outputColor;

// The slide's DepthCmp: x the tap is in front of the centre, y behind it, softly.
vec2 depthCmp(vec2 z0, vec2 z1, float softZ) { return clamp((1.0 + z0 * softZ) - z1 * softZ, 0.0, 1.0); }

// The slide's VelCmp: cones (xy) and cylinders (zw) of the tap's and the centre's |V| at a
// distance. |V| is at least a small epsilon: a still pixel covers no distance.
vec4 velCmp(float distance, vec2 speeds) {
    return clamp((1.0 - distance / max(speeds.xyxy, 1e-3)) + vec4(0.0, 0.0, 0.95, 0.95), 0.0, 1.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(outputColor);
    if (any(greaterThanEqual(pixel, size))) return;
    vec4 centre = texelFetch(colorTexture, pixel, 0);
    vec2 vN = texelFetch(neighbourMax, pixel / MOTION_BLUR_TILE_SIZE, 0).xy;
    // Early out (McGuire 2012): nothing within reach moves by half a pixel.
    if (dot(vN, vN) < 0.25) {
        imageStore(outputColor, pixel, centre);
        return;
    }
    vec2 vx = texelFetch(speedDepth, pixel, 0).xy;  // |V|, depth of the centre
    float softZ = 1.0 / (motionBlur.softDepth * vx.y);
    vec2 span = vN * motionBlur.spanScale;
    float spacing = 2.0 * length(span) / float(motionBlur.samples);
    // Taps are weighed by the length they stand for (the spacing), so the balance does not change
    // with the sample count. The centre keeps half the neighbour max velocity: a still pixel
    // beside the edge of an object moving by vN is covered half the shutter, and the taps' cones
    // add up to vN / 2 there. (McGuire's 1 / |V[X]| assumes a tap per pixel and weighs a still
    // pixel the same whatever passes over it.)
    float centreWeight = 0.5 * length(vN);
    // Sums relative to the centre: where no tap counts, the pixel stays exactly as it was.
    vec4 sum = vec4(0.0);
    float weights = centreWeight;
    vec2 x = vec2(pixel) + 0.5;
    // McGuire's per-pixel jitter of the taps by up to half their spacing: how many taps land on a
    // moving edge then varies smoothly across pixels instead of in bands (interleaved gradient
    // noise, Jimenez 2014).
    float jitter = interleavedGradientNoise(vec2(pixel)) - 0.5;
    for (int s = 0; s < motionBlur.samples; ++s) {
        float t = -1.0 + (2.0 * (float(s) + jitter) + 1.0) / float(motionBlur.samples);
        vec2 offset = span * t;
        vec2 y = x + offset;
        ivec2 tap = ivec2(floor(y));
        if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
        vec2 vy = texelFetch(speedDepth, tap, 0).xy;
        vec2 cmpZ = depthCmp(vec2(vx.y, vy.y), vec2(vy.y, vx.y), softZ);
        vec4 cmpV = velCmp(length(offset), vec2(vy.x, vx.x));
        float w = (dot(cmpZ, cmpV.xy) + cmpV.z * cmpV.w * 2.0) * spacing;
        sum += (texelFetch(colorTexture, tap, 0) - centre) * w;
        weights += w;
    }
    imageStore(outputColor, pixel, centre + sum / weights);
}
