// GPU occlusion culling (seed 004 "Occlusion culling", carried to GPU-driven rendering: Haar and
// Aaltonen 2015, "GPU-Driven Rendering Pipelines"): a compute pass over the candidate instances
// (FrameScene::occlusionCandidates) writes, per culled draw, an indexed indirect command and the
// records it draws (shaders/occlusion_cull.comp). Twice a frame: the early phase draws what the
// last frame found visible; the late phase, after the depth pyramid of the early G-buffer
// (passes/hi_z.h), draws what else is visible and stamps each instance's visibility for the next
// frame.
#pragma once

#include "gpu/frame_graph.h"
#include "passes/frame_scene.h"

#include <cstdint>
#include <string>

namespace obscura::passes {

// The stamps of visibility (a buffer of one uint per instance record, kept from frame to frame):
// `current` marks the instances this frame finds visible; those marked `last` were the last
// frame's; `last` 0: no history, the early phase draws every candidate.
struct VisibilityStamps {
    gpu::BufferHandle buffer;
    uint32_t current = 1;
    uint32_t last = 0;
};

// Clears a buffer of stamps made anew (0: no frame's) in a pass named `name`; returns its written
// version.
gpu::BufferHandle addStampsClearPass(gpu::FrameGraph& graph, gpu::BufferHandle stamps, const std::string& name);

// Adds the culling pass of `culled.phase`. `culled.commands` holds the frame's commands with no
// instance counted yet; the late phase tests against `pyramid` (passes/hi_z.h), which the early
// one binds unread. Returns `culled` with the versions the pass wrote, and `stamps` with its
// buffer's.
CulledDraws addOcclusionCullPass(gpu::FrameGraph& graph, const FrameScene& scene, CulledDraws culled,
                                 VisibilityStamps& stamps, gpu::BufferHandle pyramid);

}  // namespace obscura::passes
