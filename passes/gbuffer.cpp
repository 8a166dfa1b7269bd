#include "passes/gbuffer.h"

#include "passes/frame_data.h"

#include <cstddef>

namespace obscura::passes {
namespace {

gpu::GraphicsPipelineDesc describeGBufferPipeline() {
    gpu::GraphicsPipelineDesc d;
    d.fragmentShader = "gbuffer.frag";
    d.bindings = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}};
    d.pushedSamplers = kMaterialTextureSlots;  // set 1: the draw's material textures
    d.pushConstantSize = sizeof(uint32_t);
    setSceneVertexInput(d);
    d.colorFormats = {kNormalRoughnessFormat, kAlbedoMetallicFormat, kInstanceFormat};
    d.depthFormat = kDepthFormat;
    return d;
}

}  // namespace

void setSceneVertexInput(gpu::GraphicsPipelineDesc& d) {
    d.vertexShader = "gbuffer.vert";
    d.vertexStride = sizeof(Vertex);
    d.vertexAttributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                          {1, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                          {2, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, color)},
                          {3, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
                          {4, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)}};
}

void recordMaterialDraw(gpu::Device& device, VkCommandBuffer cmd, const gpu::Pipeline& pipeline,
                        const FrameScene& scene, const Draw& draw, const MaterialTextures*& pushed,
                        const void* push, uint32_t pushSize) {
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
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &draw.vertices->buffer, &offset);
    vkCmdBindIndexBuffer(cmd, draw.indices->buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, pushSize,
                       push);
    vkCmdDrawIndexed(cmd, draw.indexCount, draw.instanceCount, 0, 0, 0);
}

GBuffer addGBufferPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                       const gpu::ImagePtr& bestFitNormals) {
    auto image = [&](const char* name, VkFormat format) {
        gpu::ImageDesc desc;
        desc.format = format;
        desc.width = scene.width;
        desc.height = scene.height;
        return graph.createImage(name, desc);
    };
    GBuffer gb{image("gbuffer.depth", kDepthFormat), image("gbuffer.normalRoughness", kNormalRoughnessFormat),
               image("gbuffer.albedoMetallic", kAlbedoMetallicFormat), image("gbuffer.instance", kInstanceFormat)};
    const gpu::Pipeline& pipeline =
        pipelines.get<gpu::GraphicsPipelineDesc>("gbuffer", describeGBufferPipeline);
    gpu::Device& device = pipelines.device();

    graph.addPass(
        "gbuffer", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.depthStencilAttachment(gb.depth, VkClearDepthStencilValue{1.0f, 0});
            pass.colorAttachment(gb.normalRoughness, VkClearColorValue{{0.5f, 0.5f, 1.0f, 1.0f}});
            pass.colorAttachment(gb.albedoMetallic, VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}});
            pass.colorAttachment(gb.instance, VkClearColorValue{.uint32 = {0, 0, 0, 0}});
        },
        [&device, &pipeline, &scene, bestFitNormals](VkCommandBuffer cmd, const gpu::PassResources&) {
            gpu::DescriptorWriter(device, pipeline)
                .buffer(0, scene.camera->buffer)
                .buffer(1, scene.instances->buffer)
                .buffer(2, scene.materials->buffer)
                .sampled(3, bestFitNormals->view, device.nearestClampSampler())
                .bind(cmd);
            const MaterialTextures* pushed = nullptr;
            // Transparent surfaces are drawn after lighting (passes/transparent.h).
            for (const Draw& draw : scene.draws)
                if (!draw.transparent)
                    recordMaterialDraw(device, cmd, pipeline, scene, draw, pushed, &draw.instanceIndex,
                                       sizeof(uint32_t));
        });
    return gb;
}

}  // namespace obscura::passes
