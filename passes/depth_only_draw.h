// Depth-only drawing of FrameScene draws through shaders/depth_only.vert (the G-buffer's vertex
// layout and instance records, projected by a pushed view-projection): shared by the shadow maps
// and the clip volumes.
#pragma once

#include "generated/shader_layouts.h"
#include "gpu/pipeline.h"
#include "passes/frame_data.h"
#include "passes/frame_scene.h"

namespace obscura::passes {

// Mirrors the push constants of shaders/depth_only.vert.
struct DepthOnlyPush {
    Mat4 viewProjection;     // world -> clip
    uint32_t instanceIndex;  // the draw's first instance record
    // The pipeline's slope-scaled depth bias factor, for fragment stages that write their own
    // depth (sphere impostors in the shadow maps); 0 where there is none.
    float depthBiasSlope = 0.0f;
};
OBSCURA_SHADER_OFFSET(DepthOnlyPush, depth_only_vert::Push, viewProjection);
OBSCURA_SHADER_OFFSET(DepthOnlyPush, depth_only_vert::Push, instanceIndex);
OBSCURA_SHADER_OFFSET(DepthOnlyPush, depth_only_vert::Push, depthBiasSlope);

// Vertex stage, vertex layout and the push constants; callers add set 0 (the instance records at
// binding 0), the depth format and tests, and a fragment stage if they need one.
gpu::GraphicsPipelineDesc describeDepthOnlyDraw();

// Binds the draw's buffers, pushes `push` (its instanceIndex: the draw's first instance record, or
// under GPU occlusion culling its list offset), and draws every instance, or as `indirect` says.
void recordDepthOnlyDraw(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, const Draw& draw, DepthOnlyPush push,
                         const IndirectDraw* indirect = nullptr);

}  // namespace obscura::passes
