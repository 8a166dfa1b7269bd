#version 460
#extension GL_GOOGLE_include_directive : require
// Edge AA, step 1 of 3: edges by luma (Jimenez et al. 2011, "Filtering approaches for real-time
// anti-aliasing", SMAA's luma edge detection with its local contrast adaptation), kept only where
// the G-buffer also has an edge: another surface, a depth step or a crease (the comparison of the
// MSAA per-sample mask). Seed 004's edge AA "works on edges": a luma step inside a surface (a
// sharp highlight, a texture) is shading, and smoothing it only blurs it — SMAA's predicated
// thresholding, taken to its limit. Luma is taken after a Reinhard curve and a 2.2 gamma, where
// SMAA's display-space threshold applies to HDR input. Only edges that touch a pixel of an
// edge-anti-aliased instance count (hybrid AA): the rest belong to temporal AA, which has already
// supersampled them.
#include "common/edge_aa_common.glsl"
#include "common/best_fit_normals.glsl"
#include "common/frame_data.glsl"
#include "common/gbuffer_discontinuity.glsl"
#include "common/instance_target.glsl"
#include "common/view_depth.glsl"

layout(set = 0, binding = 0) uniform sampler2D color;            // HDR, pre-exposed (nearest)
layout(set = 0, binding = 1) uniform usampler2D instanceTarget;   // the G-buffer's instance target
layout(set = 0, binding = 2) uniform sampler2D depthTarget;       // the G-buffer's device depth
layout(set = 0, binding = 3) uniform sampler2D normalRoughness;   // the G-buffer's best-fit normals
layout(set = 0, binding = 4, rg8) uniform writeonly image2D edges;
CAMERA_BLOCK(5);
layout(set = 0, binding = 6, std430) readonly buffer Instances { InstanceData instances[]; };

// SMAA's defaults: a luma step of 0.1 is an edge, unless a step twice as large lies beside it
// (local contrast adaptation: the weaker of two parallel steps is shading, not a silhouette).
const float EDGE_THRESHOLD = 0.1;
const float LOCAL_CONTRAST_ADAPTATION = 2.0;

float perceptualLuma(ivec2 p, ivec2 size) {
    vec3 c = texelFetch(color, clamp(p, ivec2(0), size - 1), 0).rgb;
    float l = dot(c, vec3(0.2126, 0.7152, 0.0722));
    return pow(l / (1.0 + l), 1.0 / 2.2);
}

GBufferSample surfaceAt(ivec2 p) {
    GBufferSample g;
    g.instance = instanceIdFromTarget(texelFetch(instanceTarget, p, 0).r);
    g.viewDistance = linearDepthFromDevice(camera.projection, texelFetch(depthTarget, p, 0).r);
    g.normal = decodeBestFitNormal(texelFetch(normalRoughness, p, 0).xyz);
    return g;
}

bool edgeAntiAliased(GBufferSample g) {
    return g.instance != 0u && (instances[g.instance - 1u].flags & INSTANCE_EDGE_AA) != 0u;
}

// Whether the side between p and its neighbour q may be an edge at all.
bool geometricEdge(GBufferSample here, ivec2 q) {
    GBufferSample there = surfaceAt(q);
    return (edgeAntiAliased(here) || edgeAntiAliased(there)) && samplesDiffer(here, there);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(edges);
    if (any(greaterThanEqual(p, size))) return;
    float l = perceptualLuma(p, size);
    float left = perceptualLuma(p + ivec2(-1, 0), size), top = perceptualLuma(p + ivec2(0, -1), size);
    vec2 delta = abs(l - vec2(left, top));
    vec2 found = step(EDGE_THRESHOLD, delta);
    // An image border is no edge; nor is one between two temporally anti-aliased pixels.
    GBufferSample here = surfaceAt(p);
    if (found.x > 0.0 && (p.x == 0 || !geometricEdge(here, p + ivec2(-1, 0)))) found.x = 0.0;
    if (found.y > 0.0 && (p.y == 0 || !geometricEdge(here, p + ivec2(0, -1)))) found.y = 0.0;
    if (found == vec2(0.0)) {
        imageStore(edges, p, vec4(0.0));
        return;
    }
    float right = perceptualLuma(p + ivec2(1, 0), size), bottom = perceptualLuma(p + ivec2(0, 1), size);
    float leftLeft = perceptualLuma(p + ivec2(-2, 0), size), topTop = perceptualLuma(p + ivec2(0, -2), size);
    float strongest = max(max(max(delta.x, delta.y), max(abs(l - right), abs(l - bottom))),
                          max(abs(left - leftLeft), abs(top - topTop)));
    found *= step(strongest, LOCAL_CONTRAST_ADAPTATION * delta);
    imageStore(edges, p, vec4(found, 0.0, 0.0));
}
