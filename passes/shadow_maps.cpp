#include "passes/shadow_maps.h"

#include "passes/depth_only_draw.h"
#include "passes/shader_pass.h"

#include "gpu/content_hash.h"
#include "gpu/vulkan_functions.h"

#include <array>
#include <vector>

namespace obscura::passes {
namespace {

// Slope-scaled depth bias pushes each stored depth back by twice the depth change across one
// texel of the surface, which keeps surfaces lit at grazing angles from shadowing themselves
// (acne); the lookup adds a normal offset of its own (shadow_sampling.glsl). With a float depth
// format the constant term is one unit of the primitive's exponent: nearly nothing, as intended.
constexpr float kDepthBiasConstant = 1.0f;
constexpr float kDepthBiasSlope = 2.0f;

// Set 0: the instance records, and for cut-out draws the materials.
std::vector<ShaderBinding> shadowBindings(const SceneBuffers& buffers, bool cutout) {
    std::vector<ShaderBinding> bindings{bufferRead(buffers.instances)};
    if (cutout) bindings.push_back(bufferRead(buffers.materials));
    return bindings;
}

// Opaque draws write depth with no fragment stage; draws with an opacity cut-out add one that
// discards the texels the G-buffer discards.
gpu::GraphicsPipelineDesc describeShadowDepthPipeline(const std::vector<ShaderBinding>& bindings, bool cutout) {
    gpu::GraphicsPipelineDesc d = describeDepthOnlyDraw();
    d.bindings = bindingLayout(bindings);
    if (cutout) {
        d.fragmentShader = "shadow_cutout.frag";
        d.pushedSamplers = 1;  // set 1: the draw's opacity texture
    }
    d.depthFormat = kShadowAtlasFormat;
    d.depthBiasConstant = kDepthBiasConstant;
    d.depthBiasSlope = kDepthBiasSlope;
    return d;
}

bool casts(const Draw& draw) { return !draw.transparent; }  // docs/ARCHITECTURE.md "Transparent surfaces"

// Everything a view's depth depends on: its projection and tile, and for each caster its geometry,
// its instances' transforms and, when cut out, its material and opacity texture.
uint64_t viewKey(const FrameScene& scene, const ShadowMapView& view) {
    uint64_t h = gpu::hashValue(view.viewProjection, gpu::kContentHashSeed);
    h = gpu::hashValue(std::array<uint32_t, 3>{view.x, view.y, view.size}, h);
    for (uint32_t index : view.draws) {
        const Draw& draw = scene.draws[index];
        if (!casts(draw)) continue;
        h = gpu::hashValue(std::array<uint64_t, 4>{draw.vertices->id, draw.indices->id, draw.indexCount,
                                                   draw.opacityCutout},
                           h);
        for (uint32_t i = draw.instanceIndex; i < draw.instanceIndex + draw.instanceCount; ++i) {
            const InstanceData& instance = scene.instanceRecords.at(i);
            h = gpu::hashValue(instance.model, h);
            if (!draw.opacityCutout) continue;
            h = gpu::hashValue(scene.materialRecords.at(instance.materialIndex), h);
            h = gpu::hashValue(scene.materialTextures[draw.textures].images[kTextureOpacity]->id, h);
        }
    }
    return h;
}

// Records the draws of every view in `views` that `cutout` selects, each view into its tile.
void recordViews(VkCommandBuffer cmd, const gpu::PassResources& res, const FrameScene& scene,
                 const std::vector<uint32_t>& views, bool cutout) {
    const std::vector<ShaderBinding> bindings = shadowBindings(scene.buffers, cutout);
    const gpu::Pipeline& pipeline = res.pipelines().get<gpu::GraphicsPipelineDesc>(
        cutout ? "shadow_depth_cutout" : "shadow_depth", [&] { return describeShadowDepthPipeline(bindings, cutout); });
    bool bound = false;
    for (uint32_t v : views) {
        const ShadowMapView& view = scene.shadows.views[v];
        VkViewport viewport{float(view.x), float(view.y), float(view.size), float(view.size), 0.0f, 1.0f};
        VkRect2D tile{{int32_t(view.x), int32_t(view.y)}, {view.size, view.size}};
        DepthOnlyPush push{view.viewProjection, 0};
        bool inTile = false;
        for (uint32_t index : view.draws) {
            const Draw& draw = scene.draws[index];
            if (draw.opacityCutout != cutout || !casts(draw)) continue;
            if (!bound) {
                bindBindings(cmd, pipeline, bindings, res);
                bound = true;
            }
            if (cutout) {
                const MaterialTextures& textures = scene.materialTextures[draw.textures];
                gpu::pushSampledImages(res.device(), cmd, pipeline,
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

// A kept atlas keeps its texels outside the views rendered again: those tiles alone are cleared.
void clearTiles(VkCommandBuffer cmd, const FrameScene& scene, const std::vector<uint32_t>& views) {
    std::vector<VkClearRect> rects;
    for (uint32_t v : views) {
        const ShadowMapView& view = scene.shadows.views[v];
        rects.push_back({{{int32_t(view.x), int32_t(view.y)}, {view.size, view.size}}, 0, 1});
    }
    VkClearAttachment clear{VK_IMAGE_ASPECT_DEPTH_BIT, 0, {}};
    clear.clearValue.depthStencil = {1.0f, 0};
    if (!rects.empty()) vkCmdClearAttachments(cmd, 1, &clear, uint32_t(rects.size()), rects.data());
}

}  // namespace

gpu::ImageHandle addShadowMapPass(gpu::FrameGraph& graph, const FrameScene& scene, ShadowAtlasHistory* history) {
    gpu::ImageDesc desc;
    desc.format = kShadowAtlasFormat;
    desc.width = scene.shadows.width;
    desc.height = scene.shadows.height;
    const uint32_t viewCount = uint32_t(scene.shadows.views.size());
    std::vector<uint32_t> views;  // those to render this frame
    gpu::ImageHandle atlas;
    bool wholeAtlas = true;
    if (!history) {
        atlas = graph.createImage("shadowAtlas", desc);
        for (uint32_t v = 0; v < viewCount; ++v) views.push_back(v);
    } else {
        desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        atlas = graph.importPersistent("shadowAtlas", history->atlas, desc);
        // A new atlas (the first, or another size) holds nothing yet: every view is rendered, over
        // a cleared image.
        wholeAtlas = !history->atlas.holdsContents();
        if (wholeAtlas) history->viewKeys.clear();
        history->viewKeys.resize(viewCount, 0);
        for (uint32_t v = 0; v < viewCount; ++v) {
            const uint64_t key = viewKey(scene, scene.shadows.views[v]);
            if (!wholeAtlas && key == history->viewKeys[v]) continue;
            history->viewKeys[v] = key;
            views.push_back(v);
        }
        // Nothing changed: the kept atlas is read as it is, and no pass runs.
        if (!wholeAtlas && views.empty()) return atlas;
    }
    graph.addPass(
        "shadow_maps", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            declareBindings(pass, shadowBindings(scene.buffers, true), ShaderStage::Graphics);
            // An empty view list leaves the atlas cleared to the far depth: nothing casts.
            atlas = wholeAtlas ? pass.depthStencilAttachment(atlas, VkClearDepthStencilValue{1.0f, 0})
                               : pass.depthStencilAttachment(atlas);
        },
        [&scene, views, wholeAtlas](VkCommandBuffer cmd, const gpu::PassResources& res) {
            if (!wholeAtlas) clearTiles(cmd, scene, views);
            recordViews(cmd, res, scene, views, false);
            recordViews(cmd, res, scene, views, true);
        });
    return atlas;
}

}  // namespace obscura::passes
