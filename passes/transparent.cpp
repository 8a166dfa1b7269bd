#include "passes/transparent.h"

#include "generated/shader_layouts.h"
#include "passes/frame_data.h"
#include "passes/material_draw.h"
#include "passes/shader_pass.h"

#include <string>

namespace obscura::passes {
namespace {

struct TransparentPush {
    uint32_t instanceIndex;  // the draw's first instance record (gbuffer.vert)
    float fadeDistance;
};
OBSCURA_SHADER_OFFSET(TransparentPush, transparent_frag::Push, instanceIndex);
OBSCURA_SHADER_OFFSET(TransparentPush, transparent_frag::Push, fadeDistance);

// `spheres`: the draws are sphere impostors (the shader's SPHERE_IMPOSTOR variant);
// `cullBackFaces`: as the G-buffer does (Draw::cullBackFaces).
gpu::GraphicsPipelineDesc describeTransparentPipeline(VkFormat hdrFormat, bool spheres, bool cullBackFaces,
                                                      const std::vector<ShaderBinding>& bindings,
                                                      const std::vector<gpu::SpecializationConstant>& specialization) {
    gpu::GraphicsPipelineDesc d;
    d.specialization = specialization;
    if (cullBackFaces) d.cullMode = VK_CULL_MODE_BACK_BIT;
    setSceneVertexInput(d);
    d.fragmentShader = spheres ? "transparent_spheres.frag" : "transparent.frag";
    d.bindings = bindingLayout(bindings);
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

TransparentResult addTransparentPass(gpu::FrameGraph& graph, const FrameScene& scene,
                                     const std::vector<uint32_t>& draws, gpu::ImageHandle opaqueDepth,
                                     gpu::ImageHandle hdr, gpu::ImageHandle shadowAtlas,
                                     const EnvironmentLighting& environment, const TransparentSettings& settings) {
    gpu::ImageDesc desc;
    desc.format = kTransparentCoverageFormat;
    desc.width = scene.width;
    desc.height = scene.height;
    TransparentResult result{hdr, graph.createImage("transparentCoverage", desc)};
    const VkFormat hdrFormat = graph.imageDesc(hdr).format;
    const SceneBuffers& buffers = scene.buffers;
    std::vector<ShaderBinding> bindings{bufferRead(buffers.camera),
                                        bufferRead(buffers.instances),
                                        bufferRead(buffers.materials),
                                        bufferRead(buffers.lights),
                                        sampled(opaqueDepth),
                                        bufferRead(buffers.shadowRecords),
                                        sampled(shadowAtlas),
                                        bufferRead(buffers.environment),
                                        bufferRead(environment.irradiance),
                                        sampled(environment.prefiltered, environment.sampler)};

    // Built for the draw's material features and the frame's kinds of light: one request a draw,
    // made once here for the declaration and the recording alike.
    std::vector<gpu::PipelineCache::Request> pipelines;
    for (uint32_t index : draws) {
        const Draw& draw = scene.draws[index];
        const std::vector<gpu::SpecializationConstant> specialization{{kMaterialFeaturesConstant, draw.materialFeatures},
                                                                      {kLightKindsConstant, scene.lightKinds}};
        pipelines.push_back(gpu::PipelineCache::request<gpu::GraphicsPipelineDesc>(
            std::string(hdrFormat == VK_FORMAT_R16G16B16A16_SFLOAT ? "transparent.halfFloat" : "transparent") +
                (draw.sphereImpostors ? ".spheres" : "") + (draw.cullBackFaces ? ".backFacesCulled" : "") +
                gpu::specializationSuffix(specialization),
            [=, spheres = draw.sphereImpostors, backFaces = draw.cullBackFaces] {
                return describeTransparentPipeline(hdrFormat, spheres, backFaces, bindings, specialization);
            }));
    }
    graph.addPass(
        "transparent", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            for (const gpu::PipelineCache::Request& pipeline : pipelines) pass.usesPipeline(pipeline);
            // Attachments in the pipeline's order.
            result.hdr = pass.colorAttachment(hdr);
            result.coverage = pass.colorAttachment(result.coverage, VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}});
            declareBindings(pass, bindings, ShaderStage::Graphics);
        },
        [&scene, draws, bindings, settings, pipelines](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::Device& device = res.device();
            const gpu::Pipeline* bound = nullptr;
            const MaterialTextures* pushed = nullptr;
            // Back to front: the pipeline changes where sphere impostors and other draws, or draws of other
            // material features, alternate.
            for (size_t i = 0; i < draws.size(); ++i) {
                const Draw& draw = scene.draws[draws[i]];
                const gpu::Pipeline& pipeline = res.pipelines().get(pipelines[i]);
                if (&pipeline != bound) {
                    bindBindings(cmd, pipeline, bindings, res);
                    bound = &pipeline;
                    pushed = nullptr;  // a new layout: the pushed set starts over
                }
                TransparentPush push{draw.instanceIndex, settings.fadeDistance};
                recordMaterialDraw(device, cmd, pipeline, scene, draw, pushed, &push, sizeof(push));
            }
        });
    return result;
}

}  // namespace obscura::passes
