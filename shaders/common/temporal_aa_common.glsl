// Shared by the temporal anti-aliasing shaders (passes/temporal_aa.cpp): SMAA 1TX
// (temporal_aa.comp) and SMAA 2TX (temporal_aa_2tx.comp). Bindings 0-7 are common; the history
// images are written one texel per pixel. Colours carry coverage in alpha (1 where the G-buffer
// holds a surface, 0 where nothing drew, composited with the transparent surfaces' coverage),
// accumulated like the colour, so the premultiplied colour and its alpha stay consistent at
// anti-aliased silhouettes. Transparent surfaces are in the colour (the forward pass blended them
// into the light accumulation) but not in the depth: reprojection follows the opaque surface
// behind them, and the neighbourhood clamp bounds what a moved transparent leaves in the history.
#ifndef OBSCURA_TEMPORAL_AA_COMMON_GLSL
#define OBSCURA_TEMPORAL_AA_COMMON_GLSL

#include "common/frame_data.glsl"
#include "common/view_depth.glsl"
#include "common/coverage.glsl"
#include "common/instance_target.glsl"

// Mirrors TemporalAaConstants in passes/temporal_aa.cpp.
struct TemporalAaConstants {
    mat4 currentClipToPreviousClip;  // this frame's clip (jittered) -> last frame's, this frame's jitter added back
    mat4 currentClipToPreviousView;  // this frame's clip -> last frame's view space
    mat4 worldToPreviousClip;        // world -> last frame's clip (this frame's jitter added back)
    mat4 worldToPreviousView;        // world -> last frame's view space
    vec4 weights;                    // x K_lowfreq, y K_hifreq (1TX); z K of the 2TX velocity weight
    uvec4 frames;                    // x 1: the history may be read; y frames it holds (0: changed); z frames to converge;
                                     // w TAA_FLAG_* bits
};

// Mirrors TemporalAaFlags in passes/temporal_aa.cpp.
const uint TAA_FLAG_EDGE_AA = 1u;             // hybrid AA drew some instance for edge AA
const uint TAA_FLAG_COLOR_HAS_COVERAGE = 2u;  // currentColor carries its coverage (temporal_aa_sample.comp)

layout(local_size_x = 8, local_size_y = 8) in;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1, std140) readonly buffer Constants { TemporalAaConstants taa; };  // a storage buffer: see CAMERA_BLOCK
layout(set = 0, binding = 2) uniform sampler2D currentColor;   // the light accumulation (nearest)
layout(set = 0, binding = 3) uniform sampler2D currentDepth;   // the G-buffer's device depth (nearest)
layout(set = 0, binding = 4) uniform sampler2D previousColor;  // last frame's history colour (linear)
layout(set = 0, binding = 5) uniform sampler2D previousDepth;  // x: last frame's linear view depth (nearest)
layout(set = 0, binding = 6) uniform writeonly image2D historyColor;  // passes/temporal_aa.h temporalAaHistoryFormat
layout(set = 0, binding = 9) uniform sampler2D transparentCoverage;  // passes/transparent.h (nearest)
layout(set = 0, binding = 10) uniform usampler2D instanceTarget;     // the G-buffer's instance target
layout(set = 0, binding = 11, std430) readonly buffer Instances { InstanceData instances[]; };
layout(set = 0, binding = 12, std430) readonly buffer Reprojections { InstanceReprojection reprojections[]; };

bool historyReadable() { return taa.frames.x != 0u; }

// Hybrid AA (seed 004): the pixel's surface was drawn on the pixel grid for edge AA and keeps no
// history (the history there holds this frame's colour). Frames without hybrid AA skip the lookup.
bool edgeAntiAliased(ivec2 pixel) {
    if ((taa.frames.w & TAA_FLAG_EDGE_AA) == 0u) return false;
    uint instance = instanceIdFromTarget(texelFetch(instanceTarget, pixel, 0).r);
    return instance != 0u && (instances[instance - 1u].flags & INSTANCE_EDGE_AA) != 0u;
}

// The pixel and the slide's cross around it: its four diagonal neighbours (c_TL, c_TR, c_BL, c_BR).
const int CROSS_TAPS = 5;
const ivec2 CROSS[CROSS_TAPS] = ivec2[CROSS_TAPS](ivec2(0, 0), ivec2(-1, -1), ivec2(1, -1), ivec2(-1, 1), ivec2(1, 1));

ivec2 crossPixel(ivec2 pixel, int tap, ivec2 size) { return clamp(pixel + CROSS[tap], ivec2(0), size - 1); }

// This frame's colour at `pixel`, with coverage in alpha: composited here, or already (a still's
// sample motion-blurred before the mean, its coverage blurred along).
vec4 currentSample(ivec2 pixel, float deviceDepth) {
    vec4 colour = texelFetch(currentColor, pixel, 0);
    if ((taa.frames.w & TAA_FLAG_COLOR_HAS_COVERAGE) != 0u) return colour;
    return vec4(colour.rgb, pixelCoverage(deviceDepth, camera.backdropCoverage, transparentCoverageAt(transparentCoverage, pixel)));
}

// The workgroup's pixels and the cross's one-pixel apron around them, fetched once into shared
// memory: each pixel's cross reads five texels, so fetching per pixel read every texel five
// times, and the pass is bound by its fetches. Texels beyond the image are the edge's (as
// crossPixel clamps).
const int CROSS_TILE = 8 + 2;
shared float crossTileDepth[CROSS_TILE][CROSS_TILE];
shared bool crossTileEdgeAa[CROSS_TILE][CROSS_TILE];
shared vec4 crossTileColour[CROSS_TILE][CROSS_TILE];

// Every invocation of the workgroup calls it, before any returns (it holds a barrier); `colours`
// also fetches this frame's colour (a constant per shader, so the other builds skip it).
void loadCrossTile(ivec2 size, bool colours) {
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * 8 - 1;
    for (uint i = gl_LocalInvocationIndex; i < uint(CROSS_TILE * CROSS_TILE); i += 64u) {
        ivec2 t = ivec2(i % uint(CROSS_TILE), i / uint(CROSS_TILE));
        ivec2 texel = clamp(origin + t, ivec2(0), size - 1);
        float depth = texelFetch(currentDepth, texel, 0).r;
        crossTileDepth[t.y][t.x] = depth;
        crossTileEdgeAa[t.y][t.x] = edgeAntiAliased(texel);
        if (colours) crossTileColour[t.y][t.x] = currentSample(texel, depth);
    }
    barrier();
}

// Tap `tap` of the cross around this invocation's pixel, in the tile.
ivec2 crossTileTexel(int tap) { return ivec2(gl_LocalInvocationID.xy) + 1 + CROSS[tap]; }

// This frame's device depths over the cross (the G-buffer clears to 1, the far plane), and which
// taps hybrid AA drew on the pixel grid: those never cover a temporal pixel in any frame, so they
// neither lend it their motion nor widen its clamp (their colour would leak into its history).
struct CrossDepths {
    float depth[CROSS_TAPS];
    bool edgeAa[CROSS_TAPS];
};

CrossDepths crossDepths() {
    CrossDepths d;
    for (int i = 0; i < CROSS_TAPS; ++i) {
        ivec2 t = crossTileTexel(i);
        d.depth[i] = crossTileDepth[t.y][t.x];
        d.edgeAa[i] = crossTileEdgeAa[t.y][t.x];
    }
    return d;
}

// This frame's colour over the cross (loadCrossTile with colours).
vec4 crossColour(int tap) {
    ivec2 t = crossTileTexel(tap);
    return crossTileColour[t.y][t.x];
}

// A history depth may differ from the one expected by this much (relative) and still hold the
// same surface: float rounding through two matrices, not geometry.
const float TEMPORAL_AA_DEPTH_TOLERANCE = 0.01;

struct Reprojection {
    vec2 position;  // where the pixel's surface point lay in last frame's image, pixels (centres at +0.5)
    bool valid;     // on screen then, and the history there holds this surface
};

// Camera motion from depth: the surface point through last frame's camera. The depth is the
// front-most of the cross's: reprojecting with the nearest surface's motion (Karis 2014, "High
// quality temporal supersampling") moves a silhouette's background pixels with the object in
// front of them, so they do not take what that object covered last frame. Objects that moved on
// their own since the last frame go back along their own motion (InstanceReprojection); what a
// moving object uncovers is caught by the depth test: the history is rejected where the depth expected there
// lies outside the range of the 3x3 depths last frame stored around it. A range, not the nearest
// texel's depth, because the sub-pixel jitter moves silhouettes from frame to frame (either side
// of an edge may be what a texel saw), and a surface seen at a grazing angle changes depth
// quickly across a pixel; a disocclusion, or an object that arrived, lies outside it. Colour
// changes are the neighbourhood clamp's to handle (temporal_aa.comp).
Reprojection reproject(ivec2 pixel, ivec2 size, CrossDepths depths) {
    int nearest = 0;
    for (int i = 1; i < CROSS_TAPS; ++i)
        if (depths.depth[i] < depths.depth[nearest] && !depths.edgeAa[i]) nearest = i;
    ivec2 surfacePixel = crossPixel(pixel, nearest, size);
    vec4 clip = vec4((vec2(surfacePixel) + 0.5) / vec2(size) * 2.0 - 1.0, depths.depth[nearest], 1.0);
    vec4 previousClip = taa.currentClipToPreviousClip * clip;
    vec4 previousView = taa.currentClipToPreviousView * clip;
    // Object motion (seed 000 "SMAA 1TX": the accumulation is re-projected with camera and object
    // motion): a surface that moved since the last frame is taken back to where it was first.
    uint instance = instanceIdFromTarget(texelFetch(instanceTarget, surfacePixel, 0).r);
    uint moved = instance != 0u ? instances[instance - 1u].reprojection : 0u;
    if (moved != 0u) {
        vec4 world = camera.inverseViewProjection * clip;
        vec4 then = reprojections[moved - 1u].currentToPreviousWorld * (world / world.w);
        previousClip = taa.worldToPreviousClip * then;
        previousView = taa.worldToPreviousView * then;
    }
    Reprojection r;
    r.position = (previousClip.xy / previousClip.w * 0.5 + 0.5) * vec2(size) + vec2(pixel - surfacePixel);
    r.valid = previousClip.w > 0.0 && all(greaterThanEqual(r.position, vec2(0.0))) && all(lessThan(r.position, vec2(size)));
    if (!r.valid) return r;
    float expected = -previousView.z / previousView.w;
    // The 3x3 texels around the one the position falls in, as four gathers of 2x2 around its
    // corners (texels beyond the image are the edge's, the sampler clamping).
    ivec2 centre = ivec2(floor(r.position));
    vec4 closest = vec4(3.4e38), farthest = vec4(0.0);
    for (int j = 0; j <= 1; ++j)
        for (int i = 0; i <= 1; ++i) {
            vec4 held = textureGather(previousDepth, vec2(centre + ivec2(i, j)) / vec2(size), 0);
            closest = min(closest, held);
            farthest = max(farthest, held);
        }
    float nearestHeld = min(min(closest.x, closest.y), min(closest.z, closest.w));
    float farthestHeld = max(max(farthest.x, farthest.y), max(farthest.z, farthest.w));
    r.valid = expected >= nearestHeld * (1.0 - TEMPORAL_AA_DEPTH_TOLERANCE) &&
              expected <= farthestHeld * (1.0 + TEMPORAL_AA_DEPTH_TOLERANCE);
    return r;
}

// The history at a reprojected position through a Catmull-Rom filter (4x4 texels): a bilinear fetch
// blurs by up to half a pixel every frame the camera moves, and the accumulation compounds it;
// Catmull-Rom interpolates without that loss. Its negative lobes may overshoot at edges, which the
// neighbourhood clamp (1TX) takes back into range. The filter is separable and its two middle
// weights share a sign, so each middle pair is one bilinear fetch at their weighted position: nine
// fetches through the linear sampler instead of sixteen (the pass is bound by its fetches);
// beyond the image the sampler clamps to the edge, as the texels did.
vec4 sampleHistory(vec2 position, ivec2 size) {
    vec2 centre = position - 0.5;
    vec2 base = floor(centre);
    vec2 t = centre - base;
    // Catmull-Rom weights of the texels at -1, 0, 1, 2 from base, for fractions t.
    vec2 w0 = t * (-0.5 + t * (1.0 - 0.5 * t)), w1 = 1.0 + t * t * (-2.5 + 1.5 * t);
    vec2 w2 = t * (0.5 + t * (2.0 - 1.5 * t)), w3 = t * t * (-0.5 + 0.5 * t);
    vec2 w12 = w1 + w2;  // >= 1 for t in [0, 1]
    // Texel centres (+0.5) of the outer taps, and the middle pair's weighted position between them.
    vec2 positions[3] = vec2[3](base - 0.5, base + 0.5 + w2 / w12, base + 2.5);
    vec2 weights[3] = vec2[3](w0, w12, w3);
    vec4 sum = vec4(0.0);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
            sum += weights[i].x * weights[j].y *
                   textureLod(previousColor, vec2(positions[i].x, positions[j].y) / vec2(size), 0.0);
    return sum;
}

#endif
