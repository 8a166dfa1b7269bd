#include "passes/transparent.h"

#include "generated/shader_layouts.h"
#include "passes/frame_data.h"
#include "passes/material_draw.h"

namespace obscura::passes {
namespace {

struct TransparentPush {
    uint32_t instanceIndex;  // the draw's first instance record (gbuffer.vert)
    float fadeDistance;
};
OBSCURA_SHADER_OFFSET(TransparentPush, transparent_frag::Push, instanceIndex);
OBSCURA_SHADER_OFFSET(TransparentPush, transparent_frag::Push, fadeDistance);

gpu::GraphicsPipelineDesc describeTransparentPipeline(VkFormat hdrFormat) {
    gpu::GraphicsPipelineDesc d;
    setSceneVertexInput(d);
    d.fragmentShader = "transparent.frag";
    d.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},         {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},         {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}, {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}, {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},         {9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}};
    d.pushedSamplers = kMaterialTextureSlots;  // set 1: the draw's material textures
    d.pushConstantSize = sizeof(TransparentPush);
    d.colorFormats = {hdrFormat, kTransparentCoverageFormat};
    d.premultipliedOverBlend = true;
    // The depth test is the shader's, against the sampled opaque depth: no depth attachment.
    d.depthTest = false;
    d.depthWrite = false;
    return d;
}

}  // namespace

gpu::ImageHandle addTransparentPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                    const std::vector<uint32_t>& draws, gpu::ImageHandle opaqueDepth,
                                    gpu::ImageHandle hdr, gpu::ImageHandle shadowAtlas,
                                    const EnvironmentLighting& environment, const TransparentSettings& settings) {
    gpu::ImageDesc desc;
    desc.format = kTransparentCoverageFormat;
    desc.width = scene.width;
    desc.height = scene.height;
    gpu::ImageHandle coverage = graph.createImage("transparentCoverage", desc);
    const bool anyDraws = !draws.empty();
    VkFormat hdrFormat = graph.imageDesc(hdr).format;
    const gpu::Pipeline& pipeline = pipelines.get<gpu::GraphicsPipelineDesc>(
        hdrFormat == VK_FORMAT_R16G16B16A16_SFLOAT ? "transparent.halfFloat" : "transparent",
        [hdrFormat] { return describeTransparentPipeline(hdrFormat); });
    gpu::Device& device = pipelines.device();

    graph.addPass(
        "transparent", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            // Attachments in the pipeline's order; without draws only the coverage is cleared.
            if (anyDraws) pass.colorAttachment(hdr);
            pass.colorAttachment(coverage, VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}});
            if (!anyDraws) return;
            pass.read(opaqueDepth, gpu::Usage::SampledFragment);
            pass.read(shadowAtlas, gpu::Usage::SampledFragment);
            pass.read(environment.prefiltered, gpu::Usage::SampledFragment);
            pass.read(environment.irradiance, gpu::Usage::StorageBufferReadFragment);
        },
        [&device, &pipeline, &scene, draws, opaqueDepth, shadowAtlas, environment, settings, anyDraws](
            VkCommandBuffer cmd, const gpu::PassResources& res) {
            if (!anyDraws) return;
            VkSampler nearest = device.nearestClampSampler();
            gpu::DescriptorWriter(device, pipeline)
                .buffer(0, scene.camera->buffer)
                .buffer(1, scene.instances->buffer)
                .buffer(2, scene.materials->buffer)
                .buffer(3, scene.lights->buffer)
                .sampled(4, res.view(opaqueDepth), nearest,
                         gpu::isDepthFormat(res.desc(opaqueDepth).format) ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                                                           : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
                .buffer(5, scene.shadows.records->buffer)
                .sampled(6, res.view(shadowAtlas), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                .buffer(7, scene.environment->buffer)
                .buffer(8, res.buffer(environment.irradiance))
                .sampled(9, res.view(environment.prefiltered), environment.sampler)
                .bind(cmd);
            const MaterialTextures* pushed = nullptr;
            for (uint32_t index : draws) {
                const Draw& draw = scene.draws[index];
                TransparentPush push{draw.instanceIndex, settings.fadeDistance};
                recordMaterialDraw(device, cmd, pipeline, scene, draw, pushed, &push, sizeof(push));
            }
        });
    return coverage;
}

}  // namespace obscura::passes
