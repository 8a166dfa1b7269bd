#include "passes/gbuffer.h"

#include "generated/shader_layouts.h"
#include "passes/frame_data.h"
#include "passes/material_draw.h"

#include <cstddef>
#include <string>

namespace obscura::passes {
namespace {

enum class Variant {
    Static,                    // no velocity target
    StaticWithVelocityTarget,  // leaves the velocity target at its clear value (kStaticVelocity)
    Moving,                    // a rigid transform moves: writes velocity
    Deforming,                 // points move (a second vertex stream): writes velocity
    DeformingWithoutVelocity,  // the same in a reference sub-frame: its points at the sub-frame's time
};

const char* pipelineName(Variant variant) {
    switch (variant) {
        case Variant::Static: return "gbuffer";
        case Variant::StaticWithVelocityTarget: return "gbuffer.staticWithVelocityTarget";
        case Variant::Moving: return "gbuffer.moving";
        case Variant::Deforming: return "gbuffer.deforming";
        case Variant::DeformingWithoutVelocity: return "gbuffer.deformingWithoutVelocity";
    }
    return "";
}

// Mirrors the push constants of shaders/common/gbuffer_surface.glsl (gbuffer.vert reads the first).
struct GBufferPush {
    uint32_t instanceIndex;
    uint32_t sampleCount;
    uint32_t alphaToCoverage;
};
OBSCURA_SHADER_OFFSET(GBufferPush, gbuffer_frag::Push, instanceIndex);
OBSCURA_SHADER_OFFSET(GBufferPush, gbuffer_frag::Push, sampleCount);
OBSCURA_SHADER_OFFSET(GBufferPush, gbuffer_frag::Push, alphaToCoverage);

bool writesVelocity(Variant variant) { return variant == Variant::Moving || variant == Variant::Deforming; }
bool deforms(Variant variant) { return variant == Variant::Deforming || variant == Variant::DeformingWithoutVelocity; }

gpu::GraphicsPipelineDesc describeGBufferPipeline(Variant variant, VkSampleCountFlagBits samples) {
    gpu::GraphicsPipelineDesc d;
    d.fragmentShader = writesVelocity(variant) ? "gbuffer_moving.frag" : "gbuffer.frag";
    d.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}};
    if (writesVelocity(variant) || deforms(variant)) d.bindings.push_back({4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    d.pushedSamplers = kMaterialTextureSlots;  // set 1: the draw's material textures
    d.pushConstantSize = sizeof(GBufferPush);
    setSceneVertexInput(d);
    if (variant == Variant::Moving) d.vertexShader = "gbuffer_moving.vert";
    if (deforms(variant)) {
        d.vertexShader = "gbuffer_deforming.vert";
        d.vertexStrides.push_back(sizeof(ShutterPositions));
        d.vertexAttributes.push_back({6, VK_FORMAT_R32G32B32_SFLOAT, offsetof(ShutterPositions, open), 1});
        d.vertexAttributes.push_back({7, VK_FORMAT_R32G32B32_SFLOAT, offsetof(ShutterPositions, close), 1});
    }
    d.colorFormats = {kNormalRoughnessFormat, kAlbedoMetallicFormat, kInstanceFormat};
    if (variant != Variant::Static && variant != Variant::DeformingWithoutVelocity) d.colorFormats.push_back(kVelocityFormat);
    // Seed 000 "An improved reconstruction filter (3)": static geometry does not export velocity.
    if (variant == Variant::StaticWithVelocityTarget) d.untouchedColorAttachments = 1u << 3;
    d.depthFormat = kDepthFormat;
    d.samples = samples;
    return d;
}

Variant variantOf(const Draw& draw, bool velocityTarget) {
    if (draw.shutterPositions) return velocityTarget ? Variant::Deforming : Variant::DeformingWithoutVelocity;
    if (!velocityTarget) return Variant::Static;
    return draw.moving ? Variant::Moving : Variant::StaticWithVelocityTarget;
}

}  // namespace

GBuffer addGBufferPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                       const gpu::ImagePtr& bestFitNormals, VkSampleCountFlagBits samples, bool alphaToCoverage) {
    GBuffer gb = createGBufferImages(graph, scene, samples, "gbuffer");
    gpu::Device& device = pipelines.device();
    auto pipelineOf = [&pipelines, samples](Variant variant) -> const gpu::Pipeline& {
        return pipelines.get<gpu::GraphicsPipelineDesc>(
            std::string(pipelineName(variant)) + "." + std::to_string(samples),
            [variant, samples] { return describeGBufferPipeline(variant, samples); });
    };
    // Moving geometry is drawn last (seed 000 "An improved reconstruction filter (3)"), so static
    // surfaces never cover a velocity a moving one wrote; draws are grouped by pipeline.
    struct Ordered {
        Variant variant;
        const gpu::Pipeline* pipeline;
        const Draw* draw;
    };
    std::vector<Ordered> ordered;
    for (Variant variant : {Variant::Static, Variant::StaticWithVelocityTarget, Variant::DeformingWithoutVelocity,
                            Variant::Moving, Variant::Deforming})
        for (const Draw& draw : scene.draws)
            // Transparent surfaces are drawn after lighting (passes/transparent.h).
            if (!draw.transparent && variantOf(draw, scene.motionBlur) == variant)
                ordered.push_back({variant, &pipelineOf(variant), &draw});

    graph.addPass(
        "gbuffer", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.depthStencilAttachment(gb.depth, VkClearDepthStencilValue{1.0f, 0});
            pass.colorAttachment(gb.normalRoughness, VkClearColorValue{{0.5f, 0.5f, 1.0f, 1.0f}});
            pass.colorAttachment(gb.albedoMetallic, VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}});
            pass.colorAttachment(gb.instance, VkClearColorValue{.uint32 = {0, 0, 0, 0}});
            if (gb.velocity.valid()) pass.colorAttachment(gb.velocity, VkClearColorValue{{kStaticVelocity, 0.0f, 0.0f, 0.0f}});
        },
        [&device, ordered, &scene, bestFitNormals, samples, alphaToCoverage](VkCommandBuffer cmd,
                                                                              const gpu::PassResources&) {
            const gpu::Pipeline* bound = nullptr;
            const MaterialTextures* pushed = nullptr;
            for (auto [variant, pipeline, draw] : ordered) {
                if (pipeline != bound) {
                    gpu::DescriptorWriter writer(device, *pipeline);
                    writer.buffer(0, scene.camera->buffer)
                        .buffer(1, scene.instances->buffer)
                        .buffer(2, scene.materials->buffer)
                        .sampled(3, bestFitNormals->view, device.nearestClampSampler());
                    if (writesVelocity(variant) || deforms(variant)) writer.buffer(4, scene.instanceMotions->buffer);
                    writer.bind(cmd);
                    bound = pipeline;
                    pushed = nullptr;  // a new layout: the pushed set starts over
                }
                GBufferPush push{draw->instanceIndex, uint32_t(samples), alphaToCoverage ? 1u : 0u};
                recordMaterialDraw(device, cmd, *pipeline, scene, *draw, pushed, &push, sizeof(push));
            }
        });
    return gb;
}

}  // namespace obscura::passes
