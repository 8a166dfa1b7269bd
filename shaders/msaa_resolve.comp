#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve (seed 000 "Deferred MSAA \ custom resolve & per-sample mask":
// "pre-resolves sample 0, for pixel frequency passes"), in compute (every SM runs it; as full-screen
// raster draws it ran on the few graphics SMs some GPUs lend to raster work, TOOLCHAIN.md): sample 0
// of the normal, albedo, instance and velocity targets into the single-sample G-buffer, the
// farthest sample depth, the depth the single-sample G-buffer gets, and the per-sample mask dilated
// to 2x2 quads as the stencil value the lighting reads (MSAA_EDGE_STENCIL_BIT). Only where clip
// volumes need a depth/stencil attachment does msaa_resolve_depth.frag copy the depth and
// msaa_edge_mask.frag the mask into one.
//
// Averaging would be wrong for ids and normals and would invent depths no surface has. Depth is the
// exception where the samples agree: the rasteriser interpolates depth at each sample's own location
// while colours come from the pixel centre, and sample 0 of the standard pattern lies (-1/8, -3/8)
// pixel off the centre, so its depth put at the centre moves the point along the view ray by a
// sizeable step on grazing surfaces (enough for a shadow map to shadow a lit floor). Device depth is
// affine in window position across a triangle and the standard locations of 2, 4 and 8 samples
// average to the pixel centre, so the mean of alike samples is exactly the depth at the centre;
// where samples differ, sample 0's depth (an existing surface).
#include "common/frame_data.glsl"
#include "common/msaa_samples.glsl"

// 8x8 workgroups start at multiples of 8, so each invocation's 2x2 quad (the fragment quad the
// seed tags) lies inside its workgroup.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2DMS depthSamples;
layout(set = 0, binding = 1) uniform sampler2DMS normalRoughnessSamples;
layout(set = 0, binding = 2) uniform sampler2DMS albedoMetallicSamples;
layout(set = 0, binding = 3) uniform usampler2DMS instanceSamples;
CAMERA_BLOCK(4);
layout(set = 0, binding = 5, rgba8) uniform writeonly image2D outNormalRoughness;
// The sRGB albedo target through its UNORM view (gpu/device.h Image::storageView): encoded here.
layout(set = 0, binding = 6, rgba8) uniform writeonly image2D outAlbedoMetallic;
layout(set = 0, binding = 7, r32ui) uniform writeonly uimage2D outInstance;
layout(set = 0, binding = 8, r32f) uniform writeonly image2D outMaxDepth;
layout(set = 0, binding = 9, r32f) uniform writeonly image2D outCentreDepth;
layout(set = 0, binding = 10, r8ui) uniform writeonly uimage2D outEdgeStencil;
// Built twice (cmake variants): with VELOCITY_TARGET for a G-buffer with motion blur's velocity.
#ifdef VELOCITY_TARGET
layout(set = 0, binding = 11) uniform sampler2DMS velocitySamples;
layout(set = 0, binding = 12, rg16f) uniform writeonly image2D outVelocity;
#endif

// The sRGB transfer function (IEC 61966-2-1) the albedo target's format applies on writes: the
// fetch decoded sample 0 and 8-bit values round-trip exactly.
vec3 srgbEncode(vec3 linear) {
    return mix(12.92 * linear, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055, greaterThan(linear, vec3(0.0031308)));
}

shared bool edges[8][8];

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(pixel, textureSize(instanceSamples)));
    bool edge = false;
    if (inside) {
        edge = samplesMismatch(depthSamples, normalRoughnessSamples, instanceSamples, camera.projection, pixel);
        imageStore(outNormalRoughness, pixel, texelFetch(normalRoughnessSamples, pixel, 0));
        vec4 albedoMetallic = texelFetch(albedoMetallicSamples, pixel, 0);
        imageStore(outAlbedoMetallic, pixel, vec4(srgbEncode(albedoMetallic.rgb), albedoMetallic.a));
        imageStore(outInstance, pixel, uvec4(texelFetch(instanceSamples, pixel, 0).r));
#ifdef VELOCITY_TARGET
        imageStore(outVelocity, pixel, vec4(texelFetch(velocitySamples, pixel, 0).rg, 0.0, 0.0));
#endif
        int sampleCount = textureSamples(depthSamples);
        float sum = 0.0, farthest = 0.0;
        for (int s = 0; s < sampleCount; ++s) {
            float depth = texelFetch(depthSamples, pixel, s).r;
            sum += depth;
            farthest = max(farthest, depth);
        }
        float centre = edge ? texelFetch(depthSamples, pixel, 0).r : sum / float(sampleCount);
        imageStore(outCentreDepth, pixel, vec4(centre));
        // Seed 000 "performance shortcuts (2)": the farthest sample, for the transparents' depth
        // test and fade (passes/transparent.h).
        imageStore(outMaxDepth, pixel, vec4(farthest));
    }
    uvec2 local = gl_LocalInvocationID.xy;
    edges[local.y][local.x] = edge;
    barrier();
    // Seed 000: "tag entire pixel-quad instead of just single pixel".
    uvec2 quad = local & ~1u;
    bool quadEdge = edges[quad.y][quad.x] || edges[quad.y][quad.x + 1u] || edges[quad.y + 1u][quad.x] ||
                    edges[quad.y + 1u][quad.x + 1u];
    if (inside) imageStore(outEdgeStencil, pixel, uvec4(quadEdge ? MSAA_EDGE_STENCIL_BIT : 0u));
}
