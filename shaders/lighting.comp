#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred lighting, pixel frequency, in compute (screen-space passes run on every GPU core).
// Tiled light culling (Andersson 2011, "DirectX 11 rendering in Battlefield 3"): each 16x16 tile
// bounds its pixels' depths, keeps the local lights whose influence sphere touches that box, then
// every pixel shades with its tile's list, each light's share through its shadow maps (per pixel,
// shadow_sampling.glsl). The tile's depth range is cut into 32 slices (2.5D culling, Harada 2012,
// "A 2.5D culling for Forward+"): a light is kept only if its sphere's depth range meets a slice
// some pixel of the tile lies in, and a pixel skips the kept lights whose range misses its own
// slice, so a tile spanning a wall and the floor far behind it no longer lights both with the
// lights of either (the cost follows the lights near each surface, as clustered shading's does). Accumulates into B10G11R11_UFLOAT, pre-exposed by the camera's exposure
// (seed 004 "HDR": keep the accumulation in a range the small float format holds).
// Built twice (cmake/ObscuraShaders.cmake variants): with PER_SAMPLE_LIGHTING (render setting
// msaa > 1) pixels the custom resolve tagged in the stencil's edge bit are lit once per sample of
// the multisampled G-buffer and resolved HDR-correctly; the others stay at pixel frequency. Each
// pipeline is specialised for the kinds of light the frame holds (light_evaluation.glsl
// LIGHT_KINDS): a frame without shadow views has no shadow lookups.
#extension GL_EXT_scalar_block_layout : require
#include "common/frame_data.glsl"
#include "common/light_evaluation.glsl"
#include "common/best_fit_normals.glsl"
#include "common/ssao_upsample.glsl"
#include "common/environment_map.glsl"
#include "common/instance_target.glsl"

const uint TILE_SIZE = 16u;
const uint MAX_TILE_LIGHTS = 1024u;  // lights beyond this many in one tile are dropped
layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Materials { MaterialData materials[]; };
LIGHTS_BLOCK(3);
layout(set = 0, binding = 4) uniform sampler2D depthTexture;
layout(set = 0, binding = 5) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 6) uniform sampler2D albedoMetallicTexture;
layout(set = 0, binding = 7) uniform usampler2D instanceTexture;
// B10G11R11_UFLOAT or RGBA16F (render setting lighting:halfFloat): written without a format.
layout(set = 0, binding = 8) uniform writeonly image2D lightAccumulation;
layout(set = 0, binding = 9) uniform sampler2D ambientAccessibility;
layout(set = 0, binding = 10) uniform sampler2D ambientHalfDepth;
layout(set = 0, binding = 11, std430) readonly buffer ShadowViews { ShadowViewData shadowViews[]; };
layout(set = 0, binding = 12) uniform sampler2D shadowAtlas;
// The G-buffer's stencil: bits 0x01..0x40 mark surfaces inside the clip volumes (clip_volumes.cpp),
// 0x80 the pixels the MSAA resolve tagged for per-sample lighting (msaa_resolve.comp). The depth
// target's stencil aspect, or in a frame with MSAA and no clip volumes the resolve's R8 UINT image.
layout(set = 0, binding = 13) uniform usampler2D clipStencil;
const uint CLIP_VOLUME_BITS = 0x7fu;  // per pixel, also for the samples of tagged pixels
// The textured dome (a 1x1 black image and zero coefficients without one).
ENVIRONMENT_BLOCK(14);
layout(set = 0, binding = 15, std430) readonly buffer EnvironmentIrradiance { vec4 irradianceSh[SH_COEFFICIENTS]; };
layout(set = 0, binding = 16) uniform sampler2D prefilteredEnvironment;
#ifdef PER_SAMPLE_LIGHTING
#include "common/msaa_samples.glsl"
#include "common/hdr_resolve.glsl"
// The multisampled G-buffer the custom resolve read (msaa_resolve.frag).
layout(set = 0, binding = 17) uniform sampler2DMS depthSamples;
layout(set = 0, binding = 18) uniform sampler2DMS normalRoughnessSamples;
layout(set = 0, binding = 19) uniform sampler2DMS albedoMetallicSamples;
layout(set = 0, binding = 20) uniform usampler2DMS instanceSamples;
// Pixels lit per sample this frame (the render stats' tagged fraction).
layout(set = 0, binding = 21, std430) buffer TaggedPixels { uint taggedPixelCount; };
// The tile's tagged pixels (local invocation indices), compacted, and one round of their
// samples' weighted radiance (rgb x weight, the weight; negative where the sample hit nothing).
shared uint tileTaggedPixels;
shared uint tileTaggedList[TILE_SIZE * TILE_SIZE];
shared vec4 tileSampleRadiance[TILE_SIZE * TILE_SIZE];
#endif

// The G-buffer's textured emission, pre-exposed (passes/frame_resources.h GBuffer::emission),
// where the frame has one (EMISSION_TARGET; else the albedo stands in, unread): added for the
// materials whose emission is textured, in place of their constant (its average).
layout(constant_id = 3) const bool EMISSION_TARGET = false;
#ifdef PER_SAMPLE_LIGHTING
layout(set = 0, binding = 22) uniform sampler2DMS emissionSamples;
#else
layout(set = 0, binding = 17) uniform sampler2D emissionTexture;
#endif

#include "common/scene_lighting.glsl"

shared uint tileMinDepthBits;
shared uint tileMaxDepthBits;
shared uint tileLightCount;
shared uint tileLights[MAX_TILE_LIGHTS];
shared vec3 tileBoxMin;
shared vec3 tileBoxMax;
// The tile's depth slices: the view distances its surfaces span, the slices they occupy, and the
// slices each listed light's influence sphere reaches.
shared float tileNearDistance;
shared float tileSliceScale;
shared uint tileSliceMask;
shared uint tileLightSlices[MAX_TILE_LIGHTS];
const uint DEPTH_SLICES = 32u;

vec3 unproject(mat4 inverseMatrix, vec2 ndc, float depth) {
    vec4 p = inverseMatrix * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}

// The light's influence sphere (light_evaluation.glsl influenceSphere) against the tile's
// view-space box (tighter than the four side planes for thin tiles).
bool touchesTile(LightData light) {
    if (!isLocalLight(light)) return true;
    vec4 sphere = influenceSphere(light);
    vec3 centre = (camera.view * vec4(sphere.xyz, 1.0)).xyz;
    vec3 nearest = clamp(centre, tileBoxMin, tileBoxMax);
    vec3 d = centre - nearest;
    return dot(d, d) <= sphere.w * sphere.w;
}

// The slice of the tile's depth range holding view distance `distance`; monotonic, so a light
// whose depth range holds a point's distance has the point's slice within its own slices.
uint depthSlice(float distance) {
    return uint(clamp((distance - tileNearDistance) * tileSliceScale, 0.0, float(DEPTH_SLICES - 1u)));
}

uint depthSliceBit(float distance) { return 1u << depthSlice(distance); }

// The slices a light's influence sphere reaches (all of them for distant lights and domes).
uint lightSlices(LightData light) {
    if (!isLocalLight(light)) return ~0u;
    vec4 sphere = influenceSphere(light);
    float distance = -(camera.view * vec4(sphere.xyz, 1.0)).z;
    uint first = depthSlice(distance - sphere.w);
    uint last = depthSlice(distance + sphere.w);
    uint upToLast = last + 1u >= DEPTH_SLICES ? ~0u : (1u << (last + 1u)) - 1u;
    return upToLast & ~((1u << first) - 1u);
}

// Exposed radiance of the G-buffer surface seen through window position `windowPosition` at
// device depth `depth`, lit by the tile's lights; `instanceTarget` holds the instance (> 0) and the
// material's occlusion (instance_target.glsl), `exposedEmission` the emission target's value.
vec3 shadeSurface(uint instanceTarget, float depth, vec4 normalRoughness, vec4 albedoMetallic, vec2 windowPosition,
                  ivec2 pixel, uint insideClipVolumes, vec3 exposedEmission) {
    InstanceData inst = instances[instanceIdFromTarget(instanceTarget) - 1u];
    MaterialData mat = materials[inst.materialIndex];
    bool texturedEmission = EMISSION_TARGET && mat.textures[TEXTURE_EMISSIVE].sampled != 0u;
    vec2 ndc = windowPosition / camera.resolution * 2.0 - 1.0;
    SurfacePoint s = surfaceFromMaterial(mat, albedoMetallic.rgb, albedoMetallic.a);
    s.P = unproject(camera.inverseViewProjection, ndc, depth);
    s.N = decodeBestFitNormal(normalRoughness.xyz);
    s.V = normalize(camera.position.xyz - s.P);
    s.roughness = normalRoughness.a;
    float viewDistance = linearDepthFromDevice(camera.projection, depth);
    float screenSpaceAccess = sampleAmbientAccess(ambientAccessibility, ambientHalfDepth, pixel, viewDistance);
    s.ambientAccess = ambientAccessWithOcclusion(screenSpaceAccess, occlusionFromTarget(instanceTarget));
    s.environment = sampleEnvironment(s);
    s.shadowTurn = shadowFilterTurn(vec2(pixel), camera.noiseFrame);

    // The distant lights and the domes light every tile, the local lights those of the tile's
    // list; each loop is compiled for its own kinds of light alone (light_evaluation.glsl
    // hasLightType).
    vec3 radiance = (texturedEmission ? vec3(0.0) : mat.emissiveMetallic.rgb) +
                    reflectDistantLightsAndDomes(s, viewDistance, insideClipVolumes);
    uint count = min(tileLightCount, MAX_TILE_LIGHTS);
    uint slice = depthSliceBit(viewDistance);
    for (uint i = 0u; i < count; ++i) {
        if ((tileLightSlices[i] & slice) == 0u) continue;
        LightData light = lights[tileLights[i]];
        if (!lightReaches(light, s.P)) continue;
        radiance += clippedLight(s, light, viewDistance, insideClipVolumes, LIGHT_KINDS & LOCAL_LIGHT_KINDS);
    }
    return radiance * camera.exposureScale + (texturedEmission ? exposedEmission : vec3(0.0));
}

// What the camera sees through `windowPosition` where nothing is drawn: the visible domes
// (render setting domeLightCameraVisibility), the textured one through the mirror level of its
// prefiltered chain (the texture resampled to 512 x 256). The ray runs between two depths of the
// pixel, which serves perspective and orthographic cameras alike.
vec3 backdropRadiance(vec2 windowPosition) {
    if (environment.backdrop.w == 0.0) return vec3(0.0);
    vec3 radiance = environment.backdrop.rgb;
    if (environment.params.x > 0.5) {
        vec2 ndc = windowPosition / camera.resolution * 2.0 - 1.0;
        vec3 ray = unproject(camera.inverseViewProjection, ndc, 0.75) - unproject(camera.inverseViewProjection, ndc, 0.25);
        vec2 uv = latlongUv(normalize(mat3(environment.worldToDome) * ray));
        radiance += environment.texturedBackdrop.rgb * textureLod(prefilteredEnvironment, uv, 0.0).rgb;
    }
    return radiance * camera.exposureScale;
}

// What one invocation shades in one round: a pixel of the resolved G-buffer or a sample of the
// multisampled one (an instance target whose id is 0: nothing).
struct ShadingJob {
    uint instanceTarget;
    float depth;
    vec4 normalRoughness;
    vec4 albedoMetallic;
    vec2 windowPosition;
    ivec2 pixel;
    vec3 emission;  // the emission target's, pre-exposed
};

#ifdef PER_SAMPLE_LIGHTING
// Seed 000 "Deferred MSAA \ pixel and sample frequency passes", in compute ("DX 11.0 compute tiled
// deferred shading: loop through MSAA tagged sub-samples"). The tile's tagged pixels were compacted
// into tileTaggedList; their (pixel, sample) pairs are spread over all invocations of the tile, a
// round of TILE_SIZE^2 pairs at a time, so no invocation idles on a silhouette while its
// neighbours loop over samples (the per-sample rescheduling of Lauritzen 2010, "Deferred
// rendering for current and future rendering pipelines"). Rounds hold whole pixels: 1, 2, 4 and 8
// divide TILE_SIZE^2. Each sample is shaded at its own position (the standard sample locations).
const uint SAMPLE_ROUND = TILE_SIZE * TILE_SIZE;

// The pixel whose sample `s` this pixel resolves: its own, or under SAMPLE_RESOLVE_PIXEL_BOX the
// one whose sample `s` falls within this pixel's box this frame. The frame's jitter moved the
// image by `jitter` pixels, so the sample at window position w sees what lies at w - jitter.
ivec2 sampleSource(ivec2 pixel, int s, int sampleCount) {
    if (camera.sampleResolve != SAMPLE_RESOLVE_PIXEL_BOX) return pixel;
    vec2 jitter = camera.clipJitter * camera.resolution * 0.5;
    vec2 seen = standardSampleLocation(sampleCount, s) - jitter;
    return clamp(pixel - ivec2(floor(seen)), ivec2(0), ivec2(camera.resolution) - 1);
}

// Whether a pixel the resolve did not tag must still be lit per sample: under
// SAMPLE_RESOLVE_PIXEL_BOX a sample it takes from a neighbour differs from its own sample 0, which
// its pixel-frequency lighting shades.
bool borrowsDifferentSamples(ivec2 pixel) {
    if (camera.sampleResolve != SAMPLE_RESOLVE_PIXEL_BOX) return false;
    int sampleCount = textureSamples(instanceSamples);
    GBufferSample own =
        fetchGBufferSample(depthSamples, normalRoughnessSamples, instanceSamples, camera.projection, pixel, 0);
    for (int s = 0; s < sampleCount; ++s) {
        ivec2 source = sampleSource(pixel, s, sampleCount);
        if (source != pixel &&
            samplesDiffer(own, fetchGBufferSample(depthSamples, normalRoughnessSamples, instanceSamples,
                                                  camera.projection, source, s)))
            return true;
    }
    return false;
}

// The base colour and metallic an untagged pixel is lit with: the mean of the samples it resolves.
// Those lie on one surface (the resolve's test), but may see different colours of it: faces of
// another displayColor, or, in a still's per-sample shading, both sides of a texture's edge. The
// lighting is linear in the base colour (bilinear where metallic varies too), so the mean keeps a
// colour edge's coverage at pixel frequency, where sample 0 alone would alias it.
vec4 pixelAlbedoMetallic(ivec2 pixel) {
    int sampleCount = textureSamples(albedoMetallicSamples);
    vec4 sum = vec4(0.0);
    for (int s = 0; s < sampleCount; ++s) sum += texelFetch(albedoMetallicSamples, sampleSource(pixel, s, sampleCount), s);
    return sum / float(sampleCount);
}

// The emission an untagged pixel is lit with: the mean of the samples it resolves, as its base
// colour's (pixelAlbedoMetallic).
vec3 pixelEmission(ivec2 pixel) {
    if (!EMISSION_TARGET) return vec3(0.0);
    int sampleCount = textureSamples(emissionSamples);
    vec3 sum = vec3(0.0);
    for (int s = 0; s < sampleCount; ++s) sum += texelFetch(emissionSamples, sampleSource(pixel, s, sampleCount), s).rgb;
    return sum / float(sampleCount);
}

ShadingJob sampleJob(uint pair, uint pairs, uint sampleCount) {
    ShadingJob job;
    job.instanceTarget = 0u;
    if (pair >= pairs) return job;
    uint local = tileTaggedList[pair / sampleCount];
    int k = int(pair % sampleCount);
    // The sample is shaded where it was rasterised; resolveSampleRound stores it with its pixel.
    job.pixel = sampleSource(ivec2(gl_WorkGroupID.xy * TILE_SIZE) + ivec2(local % TILE_SIZE, local / TILE_SIZE), k,
                             int(sampleCount));
    job.instanceTarget = texelFetch(instanceSamples, job.pixel, k).r;
    job.depth = texelFetch(depthSamples, job.pixel, k).r;
    job.normalRoughness = texelFetch(normalRoughnessSamples, job.pixel, k);
    job.albedoMetallic = texelFetch(albedoMetallicSamples, job.pixel, k);
    job.windowPosition = vec2(job.pixel) + standardSampleLocation(int(sampleCount), k);
    job.emission = EMISSION_TARGET ? texelFetch(emissionSamples, job.pixel, k).rgb : vec3(0.0);
    return job;
}

// Gathers one round's sample radiance and resolves the pixels of the round with tone-mapped
// weights (hdr_resolve.glsl), or by the plain mean in a still's sample (CameraData::sampleResolve:
// the seed's weights are for few samples; the still's mean of many must stay linear to converge
// to the pixel integral); alpha is the share of samples that hit a surface. Called by every
// invocation (it holds barriers).
void resolveSampleRound(uint first, vec3 radiance, bool hit, uint sampleCount) {
    float w = camera.sampleResolve != SAMPLE_RESOLVE_TONE_MAPPED ? 1.0 : hdrResolveWeight(radiance);
    tileSampleRadiance[gl_LocalInvocationIndex] = vec4(radiance * w, hit ? w : -w);
    barrier();
    uint slot = first / sampleCount + gl_LocalInvocationIndex;
    if (gl_LocalInvocationIndex < SAMPLE_ROUND / sampleCount && slot < tileTaggedPixels) {
        vec3 weightedRadianceSum = vec3(0.0);
        float weightSum = 0.0;
        uint covered = 0u;
        for (uint k = 0u; k < sampleCount; ++k) {
            vec4 v = tileSampleRadiance[gl_LocalInvocationIndex * sampleCount + k];
            weightedRadianceSum += v.rgb;
            weightSum += abs(v.a);
            covered += v.a > 0.0 ? 1u : 0u;
        }
        uint local = tileTaggedList[slot];
        imageStore(lightAccumulation,
                   ivec2(gl_WorkGroupID.xy * TILE_SIZE) + ivec2(local % TILE_SIZE, local / TILE_SIZE),
                   vec4(hdrResolve(weightedRadianceSum, weightSum), float(covered) / float(sampleCount)));
    }
    barrier();
}
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(pixel, ivec2(camera.resolution)));
    uint instanceTarget = inside ? texelFetch(instanceTexture, pixel, 0).r : 0u;
    uint instanceId = instanceIdFromTarget(instanceTarget);
    float depth = inside ? texelFetch(depthTexture, pixel, 0).r : 1.0;

    if (gl_LocalInvocationIndex == 0u) {
        tileMinDepthBits = floatBitsToUint(1.0);
        tileMaxDepthBits = 0u;
        tileLightCount = 0u;
        tileSliceMask = 0u;
#ifdef PER_SAMPLE_LIGHTING
        tileTaggedPixels = 0u;
#endif
    }
    barrier();
    // Depths are non-negative, so their bit patterns order like the floats.
    if (instanceId != 0u) {
        atomicMin(tileMinDepthBits, floatBitsToUint(depth));
        atomicMax(tileMaxDepthBits, floatBitsToUint(depth));
    }
#ifdef PER_SAMPLE_LIGHTING
    // A tagged pixel's other samples may lie on another surface: the tile's box holds them too.
    bool perSample = inside && ((texelFetch(clipStencil, pixel, 0).r & MSAA_EDGE_STENCIL_BIT) != 0u ||
                                borrowsDifferentSamples(pixel));
    if (perSample) {
        tileTaggedList[atomicAdd(tileTaggedPixels, 1u)] = gl_LocalInvocationIndex;
        for (int k = 0; k < textureSamples(instanceSamples); ++k) {
            ivec2 source = sampleSource(pixel, k, textureSamples(instanceSamples));
            if (instanceIdFromTarget(texelFetch(instanceSamples, source, k).r) == 0u) continue;
            uint sampleDepthBits = floatBitsToUint(texelFetch(depthSamples, source, k).r);
            atomicMin(tileMinDepthBits, sampleDepthBits);
            atomicMax(tileMaxDepthBits, sampleDepthBits);
        }
    }
#endif
    barrier();
    bool tileHasSurface = tileMinDepthBits <= tileMaxDepthBits;
    if (gl_LocalInvocationIndex == 0u && tileHasSurface) {
        // Under SAMPLE_RESOLVE_PIXEL_BOX the tile's pixels take samples up to a pixel beyond it.
        float margin = camera.sampleResolve == SAMPLE_RESOLVE_PIXEL_BOX ? 1.0 : 0.0;
        vec2 tileMin = (vec2(gl_WorkGroupID.xy * TILE_SIZE) - margin) / camera.resolution * 2.0 - 1.0;
        vec2 tileMax = (vec2((gl_WorkGroupID.xy + 1u) * TILE_SIZE) + margin) / camera.resolution * 2.0 - 1.0;
        float depths[2] = float[2](uintBitsToFloat(tileMinDepthBits), uintBitsToFloat(tileMaxDepthBits));
        vec3 lo = vec3(1e30), hi = vec3(-1e30);
        for (int i = 0; i < 8; ++i) {
            vec2 ndc = vec2((i & 1) != 0 ? tileMax.x : tileMin.x, (i & 2) != 0 ? tileMax.y : tileMin.y);
            vec3 corner = unproject(camera.inverseProjection, ndc, depths[i >> 2]);
            lo = min(lo, corner);
            hi = max(hi, corner);
        }
        tileBoxMin = lo;
        tileBoxMax = hi;
        float nearDistance = linearDepthFromDevice(camera.projection, depths[0]);
        float farDistance = linearDepthFromDevice(camera.projection, depths[1]);
        tileNearDistance = min(nearDistance, farDistance);
        tileSliceScale = float(DEPTH_SLICES) / max(abs(farDistance - nearDistance), 1e-6);
    }
#ifdef PER_SAMPLE_LIGHTING
    if (gl_LocalInvocationIndex == 0u && tileTaggedPixels > 0u) atomicAdd(taggedPixelCount, tileTaggedPixels);
#endif
    barrier();
    if (instanceId != 0u) atomicOr(tileSliceMask, depthSliceBit(linearDepthFromDevice(camera.projection, depth)));
#ifdef PER_SAMPLE_LIGHTING
    if (perSample) {
        for (int k = 0; k < textureSamples(instanceSamples); ++k) {
            ivec2 source = sampleSource(pixel, k, textureSamples(instanceSamples));
            if (instanceIdFromTarget(texelFetch(instanceSamples, source, k).r) == 0u) continue;
            float sampleDistance = linearDepthFromDevice(camera.projection, texelFetch(depthSamples, source, k).r);
            atomicOr(tileSliceMask, depthSliceBit(sampleDistance));
        }
    }
#endif
    barrier();
    if (tileHasSurface) {
        // The tile's list holds the local lights (those after the distant lights and domes).
        for (uint i = distantLightCount + domeLightCount + gl_LocalInvocationIndex; i < lightCount;
             i += TILE_SIZE * TILE_SIZE) {
            if (!touchesTile(lights[i])) continue;
            uint slices = lightSlices(lights[i]);
            if ((slices & tileSliceMask) == 0u) continue;
            uint slot = atomicAdd(tileLightCount, 1u);
            if (slot < MAX_TILE_LIGHTS) {
                tileLights[slot] = i;
                tileLightSlices[slot] = slices;
            }
        }
    }
    barrier();
#ifdef PER_SAMPLE_LIGHTING
    bool pixelFrequency = inside && !perSample;
    uint sampleCount = uint(textureSamples(instanceSamples));
    uint pairs = tileTaggedPixels * sampleCount;
    uint rounds = 1u + (pairs + SAMPLE_ROUND - 1u) / SAMPLE_ROUND;
#else
    bool pixelFrequency = inside;
    const uint rounds = 1u;
#endif
    // Round 0 shades this invocation's pixel at pixel frequency, later rounds (MSAA) the tile's
    // tagged samples, through one call site of shadeSurface (its light loop inlined once).
    for (uint round = 0u; round < rounds; ++round) {
        ShadingJob job;
        job.instanceTarget = 0u;
        if (round == 0u && pixelFrequency) {
#ifdef PER_SAMPLE_LIGHTING
            vec4 albedoMetallic = pixelAlbedoMetallic(pixel);
            vec3 emission = pixelEmission(pixel);
#else
            vec4 albedoMetallic = texelFetch(albedoMetallicTexture, pixel, 0);
            vec3 emission = EMISSION_TARGET ? texelFetch(emissionTexture, pixel, 0).rgb : vec3(0.0);
#endif
            job = ShadingJob(instanceTarget, depth, texelFetch(normalRoughnessTexture, pixel, 0), albedoMetallic,
                             vec2(pixel) + 0.5, pixel, emission);
        }
#ifdef PER_SAMPLE_LIGHTING
        if (round > 0u) job = sampleJob((round - 1u) * SAMPLE_ROUND + gl_LocalInvocationIndex, pairs, sampleCount);
#endif
        bool hit = instanceIdFromTarget(job.instanceTarget) != 0u;
        vec3 radiance = hit ? shadeSurface(job.instanceTarget, job.depth, job.normalRoughness, job.albedoMetallic,
                                           job.windowPosition, job.pixel,
                                           texelFetch(clipStencil, job.pixel, 0).r & CLIP_VOLUME_BITS, job.emission)
                            : backdropRadiance(job.windowPosition);
        if (round == 0u) {
            if (pixelFrequency) imageStore(lightAccumulation, pixel, vec4(radiance, instanceId != 0u ? 1.0 : 0.0));
        }
#ifdef PER_SAMPLE_LIGHTING
        else {
            resolveSampleRound((round - 1u) * SAMPLE_ROUND, radiance, hit, sampleCount);
        }
#endif
    }
}
