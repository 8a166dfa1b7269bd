#include "passes/material_draw.h"

#include "gpu/vulkan_functions.h"
#include "passes/frame_data.h"

#include <cstddef>
#include <vector>

namespace obscura::passes {

void setSceneVertexInput(gpu::GraphicsPipelineDesc& d) {
    d.vertexShader = "gbuffer.vert";
    d.vertexStrides = {sizeof(Vertex)};
    d.vertexAttributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                          {1, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                          {2, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)},
                          {3, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
                          {4, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)}};
}

void recordMaterialDraw(gpu::Device& device, VkCommandBuffer cmd, const gpu::Pipeline& pipeline,
                        const FrameScene& scene, const Draw& draw, const MaterialTextures*& pushed,
                        const void* push, uint32_t pushSize, const IndirectDraw* indirect) {
    // Textures change per material: pushed, not allocated (VK_KHR_push_descriptor).
    const MaterialTextures& textures = scene.materialTextures[draw.textures];
    if (&textures != pushed) {
        std::vector<VkDescriptorImageInfo> images;
        for (uint32_t slot = 0; slot < kMaterialTextureSlots; ++slot)
            images.push_back(
                {textures.samplers[slot], textures.images[slot]->view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
        gpu::pushSampledImages(device, cmd, pipeline, images);
        pushed = &textures;
    }
    // A deforming draw's second stream: where its vertices are at the shutter's ends (pipelines
    // without that binding ignore it).
    VkBuffer streams[] = {draw.vertices->buffer, draw.shutterPositions ? draw.shutterPositions->buffer : VK_NULL_HANDLE};
    VkDeviceSize offsets[] = {0, 0};
    vkCmdBindVertexBuffers(cmd, 0, draw.shutterPositions ? 2 : 1, streams, offsets);
    vkCmdBindIndexBuffer(cmd, draw.indices->buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, pushSize,
                       push);
    if (indirect) vkCmdDrawIndexedIndirect(cmd, indirect->buffer, indirect->offset, 1, 0);
    else vkCmdDrawIndexed(cmd, draw.indexCount, draw.instanceCount, draw.firstIndex, 0, 0);
}

}  // namespace obscura::passes
