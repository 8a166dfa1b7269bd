// When two G-buffer samples (of one pixel under MSAA, or two neighbouring pixels) belong to
// different surfaces or to a crease of one: the geometric edges the per-sample mask of deferred
// MSAA tags (seed 000) and hybrid AA's edge AA smooths (seed 004: edge AA "works on edges").
#ifndef OBSCURA_GBUFFER_DISCONTINUITY_GLSL
#define OBSCURA_GBUFFER_DISCONTINUITY_GLSL

// What the comparison looks at in one sample of the G-buffer.
struct GBufferSample {
    uint instance;       // instance index + 1 (0: nothing); it names the material (seed 004 thin G-buffer)
    float viewDistance;  // along the view axis
    vec3 normal;
};

// Seed 000 "custom resolve & per-sample mask": "compare samples similarity, mark if mismatching",
// not the rasteriser's coverage (which tags every triangle edge, also inside one smooth surface).
// Depth differs along a slope (per sample, and from pixel to pixel): only a step of more than 10%
// of the distance counts (a surface in front of another part of the same mesh). Normals more than
// ~14 degrees apart are a crease.
const float SURFACE_DEPTH_STEP = 0.1;
const float SURFACE_CREASE_COSINE = 0.97;

bool samplesDiffer(GBufferSample a, GBufferSample b) {
    if (a.instance != b.instance) return true;
    if (a.instance == 0u) return false;  // background in both
    if (abs(a.viewDistance - b.viewDistance) > SURFACE_DEPTH_STEP * min(a.viewDistance, b.viewDistance)) return true;
    return dot(a.normal, b.normal) < SURFACE_CREASE_COSINE;
}

#endif
