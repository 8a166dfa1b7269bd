#include "passes/depth_only_draw.h"

#include "gpu/vulkan_functions.h"

#include <cstddef>

namespace obscura::passes {

gpu::GraphicsPipelineDesc describeDepthOnlyDraw() {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "depth_only.vert";
    d.pushConstantSize = sizeof(DepthOnlyPush);
    d.vertexStrides = {sizeof(Vertex)};
    d.vertexAttributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                          {3, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)}};
    return d;
}

void recordDepthOnlyDraw(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, const Draw& draw, DepthOnlyPush push,
                         const IndirectDraw* indirect) {
    if (!indirect) push.instanceIndex = draw.instanceIndex;
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &draw.vertices->buffer, &offset);
    vkCmdBindIndexBuffer(cmd, draw.indices->buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    if (indirect) vkCmdDrawIndexedIndirect(cmd, indirect->buffer, indirect->offset, 1, 0);
    else vkCmdDrawIndexed(cmd, draw.indexCount, draw.instanceCount, draw.firstIndex, 0, 0);
}

}  // namespace obscura::passes
