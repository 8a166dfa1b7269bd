#include "passes/gbuffer.h"

#include "generated/shader_layouts.h"
#include "passes/frame_data.h"
#include "passes/material_draw.h"
#include "passes/shader_pass.h"

#include <algorithm>
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

bool readsMotion(Variant variant) { return writesVelocity(variant) || deforms(variant); }

// Set 0: the camera, the records, the best-fit normal table and the lights (the principal lobe of
// anisotropic materials), and for variants that move the instances' motion.
std::vector<ShaderBinding> gbufferBindings(bool motion, const SceneBuffers& buffers, gpu::ImageHandle bestFitNormals) {
    std::vector<ShaderBinding> bindings{bufferRead(buffers.camera), bufferRead(buffers.instances),
                                        bufferRead(buffers.materials), sampled(bestFitNormals),
                                        bufferRead(buffers.lights)};
    if (motion) bindings.push_back(bufferRead(buffers.instanceMotions));
    return bindings;
}

// `cutout`: the draw's material has an opacity threshold; the other draws take the shaders'
// OPAQUE_SURFACE variant, whose depth test runs before shading (common/gbuffer_surface.glsl).
gpu::GraphicsPipelineDesc describeGBufferPipeline(Variant variant, bool cutout, VkSampleCountFlagBits samples,
                                                  const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d;
    d.fragmentShader = std::string(writesVelocity(variant) ? "gbuffer_moving" : "gbuffer") +
                       (cutout ? ".frag" : "_opaque.frag");
    d.bindings = bindingLayout(bindings);
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
    if (variant != Variant::Static && variant != Variant::DeformingWithoutVelocity)
        d.colorFormats.push_back(kVelocityFormat);
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

GBuffer addGBufferPass(gpu::FrameGraph& graph, const FrameScene& scene, gpu::ImageHandle bestFitNormals,
                       VkSampleCountFlagBits samples, bool alphaToCoverage) {
    GBuffer gb = createGBufferImages(graph, scene, samples, "gbuffer");
    // Moving geometry is drawn last (seed 000 "An improved reconstruction filter (3)"), so static
    // surfaces never cover a velocity a moving one wrote; draws are grouped by pipeline.
    // Within a variant, opaque draws come before cut-outs: what they hide is then never shaded.
    struct Ordered {
        Variant variant;
        const Draw* draw;
    };
    std::vector<Ordered> ordered;
    for (Variant variant : {Variant::Static, Variant::StaticWithVelocityTarget, Variant::DeformingWithoutVelocity,
                            Variant::Moving, Variant::Deforming})
        for (bool cutout : {false, true})
            for (const Draw& draw : scene.cameraDraws)
                // Transparent surfaces are drawn after lighting (passes/transparent.h).
                if (!draw.transparent && draw.opacityCutout == cutout && variantOf(draw, scene.motionBlur) == variant)
                    ordered.push_back({variant, &draw});
    const bool anyMotion =
        std::any_of(ordered.begin(), ordered.end(), [](const Ordered& o) { return readsMotion(o.variant); });

    graph.addPass(
        "gbuffer", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            declareBindings(pass, gbufferBindings(anyMotion, scene.buffers, bestFitNormals), ShaderStage::Graphics);
            gb.depth = pass.depthStencilAttachment(gb.depth, VkClearDepthStencilValue{1.0f, 0});
            gb.normalRoughness = pass.colorAttachment(gb.normalRoughness, VkClearColorValue{{0.5f, 0.5f, 1.0f, 1.0f}});
            gb.albedoMetallic = pass.colorAttachment(gb.albedoMetallic, VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}});
            gb.instance = pass.colorAttachment(gb.instance, VkClearColorValue{.uint32 = {0, 0, 0, 0}});
            if (gb.velocity.valid())
                gb.velocity =
                    pass.colorAttachment(gb.velocity, VkClearColorValue{{kStaticVelocity, 0.0f, 0.0f, 0.0f}});
        },
        [ordered, &scene, bestFitNormals, samples, alphaToCoverage](VkCommandBuffer cmd,
                                                                     const gpu::PassResources& res) {
            gpu::Device& device = res.device();
            const gpu::Pipeline* bound = nullptr;
            Variant boundVariant = Variant::Static;
            bool boundCutout = false;
            const MaterialTextures* pushed = nullptr;
            for (const Ordered& o : ordered) {
                // Draws come grouped by variant: the pipeline changes only between groups.
                const bool cutout = o.draw->opacityCutout;
                if (!bound || o.variant != boundVariant || cutout != boundCutout) {
                    const std::vector<ShaderBinding> bindings =
                        gbufferBindings(readsMotion(o.variant), scene.buffers, bestFitNormals);
                    bound = &res.pipelines().get<gpu::GraphicsPipelineDesc>(
                        std::string(pipelineName(o.variant)) + (cutout ? ".cutout." : ".") + std::to_string(samples),
                        [&] { return describeGBufferPipeline(o.variant, cutout, samples, bindings); });
                    boundVariant = o.variant;
                    boundCutout = cutout;
                    bindBindings(cmd, *bound, bindings, res);
                    pushed = nullptr;  // a new layout: the pushed set starts over
                }
                GBufferPush push{o.draw->instanceIndex, uint32_t(samples), alphaToCoverage ? 1u : 0u};
                recordMaterialDraw(device, cmd, *bound, scene, *o.draw, pushed, &push, sizeof(push));
            }
        });
    return gb;
}

}  // namespace obscura::passes
