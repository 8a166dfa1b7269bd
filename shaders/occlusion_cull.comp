#version 460
#extension GL_GOOGLE_include_directive : require
// GPU occlusion culling (passes/occlusion_cull.h), the two-phase route of GPU-driven pipelines
// (Haar and Aaltonen 2015, "GPU-Driven Rendering Pipelines"), one invocation per candidate
// instance:
// - early phase: the instances the last frame found visible are drawn at once, untested; their
//   depth is this frame's first occluders.
// - late phase (after the depth pyramid of that depth, common/hi_z.glsl): every candidate's world
//   bounds are tested against the pyramid; a visible one the early phase did not draw is drawn
//   now, and each is stamped visible or not for the next frame.
// What the late phase culls is hidden behind depth this frame really has, so nothing visible is
// ever left out (seed 004's coverage buffer tests last frame's depth instead and may be wrong where
// the view changed). Each drawn instance appends its record to its draw's list and counts itself
// into the draw's indirect command. SHADOW_VIEWS (occlusion_cull_shadow.comp): the candidates of
// the shadow atlas's views, each command a draw into one view, tested against the atlas's pyramid
// within the view's tile; their stamps are kept per view and record.
#include "common/frame_data.glsl"
#include "common/hi_z.glsl"

layout(local_size_x = 256) in;

layout(set = 0, binding = 0, std430) readonly buffer Candidates { OcclusionCandidate candidates[]; };
layout(set = 0, binding = 1, std430) buffer Commands { CulledDrawCommand commands[]; };
layout(set = 0, binding = 2, std430) writeonly buffer Lists { uint drawnRecords[]; };
// Per instance record: the stamp of the last frame that found it visible.
layout(set = 0, binding = 3, std430) buffer Visibility { uint visibleStamp[]; };
#ifdef SHADOW_VIEWS
layout(set = 0, binding = 4, std430) readonly buffer ShadowViews { ShadowViewData views[]; };
#else
CAMERA_BLOCK(4);
#endif
layout(set = 0, binding = 5, std430) readonly buffer Pyramid { float farthest[]; };

layout(push_constant) uniform Push {
    uint candidateCount;
    uint late;          // 0: the early phase, 1: the late one
    uint commandCount;  // commands of one phase: the late phase's follow the early's
    uint stamp;         // this frame's
    uint lastStamp;     // the last frame's; 0: no history, the early phase draws every candidate
    uint recordCount;   // instance records: a shadow view's stamps follow the previous view's
    uvec2 pixels;       // the depth's size (the atlas's)
} push;

// Pixels a box's screen rectangle grows by: the instances hybrid AA draws unjittered lie up to
// half a pixel from where the jittered projection puts them, and MSAA samples anywhere in a pixel.
const float kMarginPixels = 1.0;
// Device depth a box must lie behind its occluder by: the box's corners are projected here in
// single precision, the occluder's depth was interpolated by the rasteriser.
const float kDepthMargin = 1.0 / 1048576.0;

// Whether the box lies behind the pyramid's farthest depth over every pixel it may cover.
// `toPixels`: world -> clip whose x/w, y/w are pixel coordinates and z/w the depth; `tile`: the
// first and the last pixel the view draws into.
bool hidden(vec3 boxMin, vec3 boxMax, mat4 toPixels, ivec4 tile) {
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    float nearest = 1.0;
    for (uint c = 0u; c < 8u; ++c) {
        vec3 corner = vec3((c & 1u) != 0u ? boxMax.x : boxMin.x, (c & 2u) != 0u ? boxMax.y : boxMin.y,
                           (c & 4u) != 0u ? boxMax.z : boxMin.z);
        vec4 clip = toPixels * vec4(corner, 1.0);
        // A box reaching the eye's plane or the near plane is never hidden.
        if (clip.w <= 0.0 || clip.z < 0.0) return false;
        vec3 projected = clip.xyz / clip.w;
        lo = min(lo, projected.xy);
        hi = max(hi, projected.xy);
        nearest = min(nearest, projected.z);
    }
    ivec2 first = max(ivec2(floor(lo - kMarginPixels)), tile.xy);
    ivec2 last = min(ivec2(floor(hi + kMarginPixels)), tile.zw);
    if (any(greaterThan(first, last))) return false;
    // The finest level at which the rectangle spans at most two texels a side.
    uint span = uint(max(last.x - first.x, last.y - first.y));
    uint level = span <= 2u ? 1u : uint(findMSB(span - 1u)) + 1u;
    level = min(level, hiZTopLevel(push.pixels));
    uvec2 lo2 = uvec2(first) >> level, hi2 = uvec2(last) >> level;
    uvec2 levelSize = hiZLevelSize(push.pixels, level);
    uint offset = hiZLevelOffset(push.pixels, level);
    float occluder = 0.0;
    for (uint y = lo2.y; y <= hi2.y; ++y)
        for (uint x = lo2.x; x <= hi2.x; ++x) occluder = max(occluder, farthest[offset + y * levelSize.x + x]);
    return nearest > occluder + kDepthMargin;
}

// The candidate's box tested in its view: the camera's, or its command's shadow view.
bool hidden(OcclusionCandidate candidate) {
#ifdef SHADOW_VIEWS
    ShadowViewData view = views[commands[candidate.command].view];
    return hidden(candidate.boundsMin, candidate.boundsMax, view.worldToAtlas, ivec4(view.tileRect));
#else
    // Clip to pixels: x' = (x/w * 0.5 + 0.5) * width, as the viewport maps them.
    vec2 size = vec2(push.pixels);
    mat4 toPixels = mat4(vec4(0.5 * size.x, 0.0, 0.0, 0.0), vec4(0.0, 0.5 * size.y, 0.0, 0.0),
                         vec4(0.0, 0.0, 1.0, 0.0), vec4(0.5 * size, 0.0, 1.0)) * camera.viewProjection;
    return hidden(candidate.boundsMin, candidate.boundsMax, toPixels, ivec4(0, 0, ivec2(push.pixels) - 1));
#endif
}

// Where the candidate's stamp is: per record, and for shadow views per view too.
uint stampIndex(OcclusionCandidate candidate) {
#ifdef SHADOW_VIEWS
    return commands[candidate.command].view * push.recordCount + candidate.record;
#else
    return candidate.record;
#endif
}

void draw(OcclusionCandidate candidate) {
    uint command = candidate.command + push.late * push.commandCount;
    uint slot = atomicAdd(commands[command].instanceCount, 1u);
    drawnRecords[commands[command].listOffset + slot] = candidate.record;
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= push.candidateCount) return;
    OcclusionCandidate candidate = candidates[index];
    uint stamp = stampIndex(candidate);
    bool drawnEarly = push.lastStamp == 0u || visibleStamp[stamp] == push.lastStamp;
    if (push.late == 0u) {
        if (drawnEarly) draw(candidate);
        return;
    }
    if (hidden(candidate)) return;
    visibleStamp[stamp] = push.stamp;
    if (!drawnEarly) draw(candidate);
}
