// Shared by the edge AA passes (passes/edge_aa.cpp), hybrid AA's post-process anti-aliasing for
// near objects (seed 004 "Hybrid anti-aliasing solution": "post-process AA for near objects:
// doesn't supersample, works on edges"). The edges image holds, per pixel, whether an edge runs
// along its left side (r) and its top side (g); the weights image, how much of each neighbour
// across those edges the pixel and that neighbour take (passes/edge_aa.h).
#ifndef OBSCURA_EDGE_AA_COMMON_GLSL
#define OBSCURA_EDGE_AA_COMMON_GLSL

layout(local_size_x = 8, local_size_y = 8) in;

bool insideImage(ivec2 p, ivec2 size) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, size)); }

#endif
