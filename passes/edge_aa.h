// Edge AA (frame step 9b, after temporal AA, only when hybrid AA tagged an instance): the
// post-process half of seed 004's "Hybrid anti-aliasing solution" — near objects are drawn without
// the jitter and keep no temporal history (view-dependent shading defeats reprojection there), and
// their edges are anti-aliased in screen space instead; distant objects stay temporal. Morphological
// AA (MLAA / SMAA 1x's spatial steps), three compute passes:
//   edge_aa_edges    luma edges where the G-buffer has one too, touching an edge-anti-aliased pixel;
//   edge_aa_weights  per edge, its ends, its pattern and the reconstructed silhouette's areas;
//   edge_aa_blend    each pixel mixed with its neighbours across its edges by those areas.
#pragma once

#include "passes/frame_scene.h"
#include "passes/frame_resources.h"

namespace obscura::passes {

// Reads the anti-aliased HDR colour (RGBA16F, coverage in alpha) and the G-buffer's instance target,
// depth and normals; returns a new RGBA16F image.
gpu::ImageHandle addEdgeAaPasses(gpu::FrameGraph& graph, const FrameScene& scene,
                                 const GBuffer& gbuffer, gpu::ImageHandle hdrColor);

}  // namespace obscura::passes
