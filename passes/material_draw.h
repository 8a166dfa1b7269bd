// Drawing FrameScene draws with their materials through the scene's vertex layout
// (shaders/gbuffer.vert): shared by the G-buffer and the transparent pass.
#pragma once

#include "gpu/pipeline.h"
#include "passes/frame_scene.h"

namespace obscura::passes {

// The scene's vertex input (Vertex, the instance records; shaders/gbuffer.vert), shared by the
// passes that draw the scene's materials.
void setSceneVertexInput(gpu::GraphicsPipelineDesc& desc);

// Records one draw of the scene with its material textures pushed into set 1 (unless `pushed`
// holds them already) and `push` as push constants (its first uint: the draw's first instance),
// with its own counts, or those of `indirect`.
void recordMaterialDraw(gpu::Device& device, VkCommandBuffer cmd, const gpu::Pipeline& pipeline,
                        const FrameScene& scene, const Draw& draw, const MaterialTextures*& pushed,
                        const void* push, uint32_t pushSize, const IndirectDraw* indirect = nullptr);

}  // namespace obscura::passes
