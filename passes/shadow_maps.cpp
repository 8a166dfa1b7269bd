#include "passes/shadow_maps.h"

#include "passes/depth_only_draw.h"

namespace obscura::passes {
namespace {

// Slope-scaled depth bias pushes each stored depth back by twice the depth change across one
// texel of the surface, which keeps surfaces lit at grazing angles from shadowing themselves
// (acne); the lookup adds a normal offset of its own (shadow_sampling.glsl). With a float depth
// format the constant term is one unit of the primitive's exponent: nearly nothing, as intended.
constexpr float kDepthBiasConstant = 1.0f;
constexpr float kDepthBiasSlope = 2.0f;

// Opaque draws write depth with no fragment stage; draws with an opacity cut-out add one that
// discards the texels the G-buffer discards.
gpu::GraphicsPipelineDesc describeShadowDepthPipeline(bool cutout) {
    gpu::GraphicsPipelineDesc d = describeDepthOnlyDraw();
    if (cutout) {
        d.fragmentShader = "shadow_cutout.frag";
        d.bindings.push_back({1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        d.pushedSamplers = 1;  // set 1: the draw's opacity texture
    }
    d.depthFormat = kShadowAtlasFormat;
    d.depthBiasConstant = kDepthBiasConstant;
    d.depthBiasSlope = kDepthBiasSlope;
    return d;
}

// Records the draws of every view that `cutout` selects, each view into its tile.
void recordViews(gpu::Device& device, VkCommandBuffer cmd, const gpu::Pipeline& pipeline, const FrameScene& scene,
                 bool cutout) {
    bool bound = false;
    for (const ShadowMapView& view : scene.shadows.views) {
        VkViewport viewport{float(view.x), float(view.y), float(view.size), float(view.size), 0.0f, 1.0f};
        VkRect2D tile{{int32_t(view.x), int32_t(view.y)}, {view.size, view.size}};
        DepthOnlyPush push{view.viewProjection, 0};
        bool inTile = false;
        for (uint32_t index : view.draws) {
            const Draw& draw = scene.draws[index];
            // Transparent surfaces cast no shadow (docs/ARCHITECTURE.md "Transparent surfaces").
            if (draw.opacityCutout != cutout || draw.transparent) continue;
            if (!bound) {
                gpu::DescriptorWriter writer(device, pipeline);
                writer.buffer(0, scene.instances->buffer);
                if (cutout) writer.buffer(1, scene.materials->buffer);
                writer.bind(cmd);
                bound = true;
            }
            if (cutout) {
                const MaterialTextures& textures = scene.materialTextures[draw.textures];
                gpu::pushSampledImages(device, cmd, pipeline,
                                       {{textures.samplers[kTextureOpacity], textures.images[kTextureOpacity]->view,
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}});
            }
            if (!inTile) {
                vkCmdSetViewport(cmd, 0, 1, &viewport);
                vkCmdSetScissor(cmd, 0, 1, &tile);
                inTile = true;
            }
            recordDepthOnlyDraw(cmd, pipeline, draw, push);
        }
    }
}

}  // namespace

gpu::ImageHandle addShadowMapPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene) {
    gpu::ImageDesc desc;
    desc.format = kShadowAtlasFormat;
    desc.width = scene.shadows.width;
    desc.height = scene.shadows.height;
    gpu::ImageHandle atlas = graph.createImage("shadowAtlas", desc);
    const gpu::Pipeline& opaque = pipelines.get<gpu::GraphicsPipelineDesc>(
        "shadow_depth", [] { return describeShadowDepthPipeline(false); });
    const gpu::Pipeline& cutout = pipelines.get<gpu::GraphicsPipelineDesc>(
        "shadow_depth_cutout", [] { return describeShadowDepthPipeline(true); });
    gpu::Device& device = pipelines.device();

    // An empty view list leaves the atlas cleared to the far depth: nothing casts.
    graph.addPass(
        "shadow_maps", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) { pass.depthStencilAttachment(atlas, VkClearDepthStencilValue{1.0f, 0}); },
        [&device, &opaque, &cutout, &scene](VkCommandBuffer cmd, const gpu::PassResources&) {
            recordViews(device, cmd, opaque, scene, false);
            recordViews(device, cmd, cutout, scene, true);
        });
    return atlas;
}

}  // namespace obscura::passes
