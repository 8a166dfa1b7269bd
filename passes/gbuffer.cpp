#include "passes/gbuffer.h"

#include "passes/frame_data.h"

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
    // A deforming draw's second stream: where its vertices are at the shutter's ends (pipelines
    // without that binding ignore it).
    VkBuffer streams[] = {draw.vertices->buffer, draw.shutterPositions ? draw.shutterPositions->buffer : VK_NULL_HANDLE};
    VkDeviceSize offsets[] = {0, 0};
    vkCmdBindVertexBuffers(cmd, 0, draw.shutterPositions ? 2 : 1, streams, offsets);
    vkCmdBindIndexBuffer(cmd, draw.indices->buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, pushSize,
                       push);
    vkCmdDrawIndexed(cmd, draw.indexCount, draw.instanceCount, 0, 0, 0);
}

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
    GBuffer gb{image("depth", kDepthFormat), image("normalRoughness", kNormalRoughnessFormat),
               image("albedoMetallic", kAlbedoMetallicFormat), image("instance", kInstanceFormat), {}};
    if (scene.motionBlur) gb.velocity = image("velocity", kVelocityFormat);
    return gb;
}

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
