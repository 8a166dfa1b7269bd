#include "passes/shadow_maps.h"

#include "passes/frame_data.h"

#include <cstddef>

namespace obscura::passes {
namespace {

struct ShadowDepthPush {
    Mat4 viewProjection;
    uint32_t instanceIndex;
};

// Slope-scaled depth bias pushes each stored depth back by twice the depth change across one
// texel of the surface, which keeps surfaces lit at grazing angles from shadowing themselves
// (acne); the lookup adds a normal offset of its own (shadow_sampling.glsl). With a float depth
// format the constant term is one unit of the primitive's exponent: nearly nothing, as intended.
constexpr float kDepthBiasConstant = 1.0f;
constexpr float kDepthBiasSlope = 2.0f;

gpu::GraphicsPipelineDesc describeShadowDepthPipeline() {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "shadow_depth.vert";
    d.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    d.pushConstantSize = sizeof(ShadowDepthPush);
    d.vertexStride = sizeof(Vertex);
    d.vertexAttributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)}};
    d.depthFormat = kShadowAtlasFormat;
    d.depthBiasConstant = kDepthBiasConstant;
    d.depthBiasSlope = kDepthBiasSlope;
    return d;
}

}  // namespace

gpu::ImageHandle addShadowMapPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene) {
    gpu::ImageDesc desc;
    desc.format = kShadowAtlasFormat;
    desc.width = scene.shadows.width;
    desc.height = scene.shadows.height;
    gpu::ImageHandle atlas = graph.createImage("shadowAtlas", desc);
    const gpu::Pipeline& pipeline =
        pipelines.get<gpu::GraphicsPipelineDesc>("shadow_depth", describeShadowDepthPipeline);
    gpu::Device& device = pipelines.device();

    graph.addPass(
        "shadow_maps", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) { pass.depthStencilAttachment(atlas, VkClearDepthStencilValue{1.0f, 0}); },
        [&device, &pipeline, &scene](VkCommandBuffer cmd, const gpu::PassResources&) {
            if (scene.shadows.views.empty()) return;  // the cleared atlas: nothing casts
            gpu::DescriptorWriter(device, pipeline).buffer(0, scene.instances->buffer).bind(cmd);
            for (const ShadowMapView& view : scene.shadows.views) {
                VkViewport viewport{float(view.x), float(view.y), float(view.size), float(view.size), 0.0f, 1.0f};
                VkRect2D tile{{int32_t(view.x), int32_t(view.y)}, {view.size, view.size}};
                vkCmdSetViewport(cmd, 0, 1, &viewport);
                vkCmdSetScissor(cmd, 0, 1, &tile);
                ShadowDepthPush push{view.viewProjection, 0};
                for (uint32_t index : view.draws) {
                    const Draw& draw = scene.draws[index];
                    push.instanceIndex = draw.instanceIndex;
                    VkDeviceSize offset = 0;
                    vkCmdBindVertexBuffers(cmd, 0, 1, &draw.vertices->buffer, &offset);
                    vkCmdBindIndexBuffer(cmd, draw.indices->buffer, 0, VK_INDEX_TYPE_UINT32);
                    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                       0, sizeof(push), &push);
                    vkCmdDrawIndexed(cmd, draw.indexCount, draw.instanceCount, 0, 0, 0);
                }
            }
        });
    return atlas;
}

}  // namespace obscura::passes
