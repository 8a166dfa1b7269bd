#include "passes/gbuffer.h"

#include "passes/frame_data.h"

#include <cstddef>
#include <string>

namespace obscura::passes {
namespace {

gpu::GraphicsPipelineDesc describeGBufferPipeline(VkSampleCountFlagBits samples) {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "gbuffer.vert";
    d.fragmentShader = "gbuffer.frag";
    d.bindings = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}};
    d.pushedSamplers = kMaterialTextureSlots;  // set 1: the draw's material textures
    d.pushConstantSize = sizeof(uint32_t);
    d.vertexStride = sizeof(Vertex);
    d.vertexAttributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                          {1, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                          {2, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, color)},
                          {3, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
                          {4, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)}};
    d.colorFormats = {kNormalRoughnessFormat, kAlbedoMetallicFormat, kInstanceFormat};
    d.depthFormat = kDepthFormat;
    d.samples = samples;
    return d;
}

}  // namespace

GBuffer createGBufferImages(gpu::FrameGraph& graph, const FrameScene& scene, VkSampleCountFlagBits samples,
                            const std::string& prefix) {
    auto image = [&](const char* name, VkFormat format) {
        gpu::ImageDesc desc;
        desc.format = format;
        desc.width = scene.width;
        desc.height = scene.height;
        desc.samples = samples;
        return graph.createImage(prefix + "." + name, desc);
    };
    return {image("depth", kDepthFormat), image("normalRoughness", kNormalRoughnessFormat),
            image("albedoMetallic", kAlbedoMetallicFormat), image("instance", kInstanceFormat)};
}

GBuffer addGBufferPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                       const gpu::ImagePtr& bestFitNormals, VkSampleCountFlagBits samples) {
    GBuffer gb = createGBufferImages(graph, scene, samples, "gbuffer");
    const gpu::Pipeline& pipeline = pipelines.get<gpu::GraphicsPipelineDesc>(
        "gbuffer." + std::to_string(samples), [samples] { return describeGBufferPipeline(samples); });
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
            for (const Draw& draw : scene.draws) {
                // Textures change per material: pushed, not allocated (VK_KHR_push_descriptor).
                const MaterialTextures& textures = scene.materialTextures[draw.textures];
                if (&textures != pushed) {
                    std::vector<VkDescriptorImageInfo> images;
                    for (uint32_t slot = 0; slot < kMaterialTextureSlots; ++slot)
                        images.push_back({textures.samplers[slot], textures.images[slot]->view,
                                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
                    gpu::pushSampledImages(device, cmd, pipeline, images);
                    pushed = &textures;
                }
                VkDeviceSize offset = 0;
                vkCmdBindVertexBuffers(cmd, 0, 1, &draw.vertices->buffer, &offset);
                vkCmdBindIndexBuffer(cmd, draw.indices->buffer, 0, VK_INDEX_TYPE_UINT32);
                vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                   sizeof(uint32_t), &draw.instanceIndex);
                vkCmdDrawIndexed(cmd, draw.indexCount, draw.instanceCount, 0, 0, 0);
            }
        });
    return gb;
}

}  // namespace obscura::passes
