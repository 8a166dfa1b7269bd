#include "passes/shadow_maps.h"

#include "passes/depth_only_draw.h"
#include "passes/shader_pass.h"

#include "gpu/content_hash.h"
#include "gpu/vulkan_functions.h"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace obscura::passes {
namespace {

// Slope-scaled depth bias pushes each stored depth back by twice the depth change across one
// texel of the surface, which keeps surfaces lit at grazing angles from shadowing themselves
// (acne); the lookup adds a normal offset of its own (shadow_sampling.glsl). With a float depth
// format the constant term is one unit of the primitive's exponent: nearly nothing, as intended.
constexpr float kDepthBiasConstant = 1.0f;
constexpr float kDepthBiasSlope = 2.0f;

// How a caster's fragments make its depth: the rasteriser's alone (opaque), cut out by its
// material's opacity threshold, or sphere impostors (the sphere each cube bounds, its depth
// written by the fragment stage; a cut-out material cuts them too).
enum class Caster { Opaque, Cutout, Spheres };

Caster casterOf(const Draw& draw) {
    if (draw.sphereImpostors) return Caster::Spheres;
    return draw.opacityCutout ? Caster::Cutout : Caster::Opaque;
}

// Set 0: the instance records, for cut-out draws and sphere impostors the materials, and for draws
// culled on the GPU the records the culling pass left them.
std::vector<ShaderBinding> shadowBindings(const SceneBuffers& buffers, Caster caster,
                                          const CulledDraws* culled = nullptr) {
    std::vector<ShaderBinding> bindings{bufferRead(buffers.instances),
                                        caster != Caster::Opaque ? bufferRead(buffers.materials) : unbound()};
    if (culled) bindings.push_back(bufferRead(culled->lists));
    return bindings;
}

// Opaque draws write depth with no fragment stage; draws with an opacity cut-out add one that
// discards the texels the G-buffer discards, sphere impostors its variant that writes the depth of
// their spheres.
gpu::GraphicsPipelineDesc describeShadowDepthPipeline(const std::vector<ShaderBinding>& bindings, Caster caster,
                                                      bool culled, bool cullBackFaces) {
    gpu::GraphicsPipelineDesc d = describeDepthOnlyDraw();
    if (cullBackFaces) d.cullMode = VK_CULL_MODE_BACK_BIT;
    if (culled) d.vertexShader = "depth_only_culled.vert";
    d.bindings = bindingLayout(bindings);
    if (caster != Caster::Opaque) {
        d.fragmentShader = "shadow_cutout.frag";
        d.pushedSamplers = 1;  // set 1: the draw's opacity texture
    }
    if (caster == Caster::Spheres) {
        d.vertexShader = culled ? "depth_only_culled_spheres.vert" : "depth_only_spheres.vert";
        d.fragmentShader = "shadow_cutout_spheres.frag";
        d.vertexAttributes.push_back({4, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)});
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

// Whether the draw numbered `i` in `view` is culled on the GPU.
bool culledInView(const ShadowMapView& view, size_t i) {
    return !view.culled.empty() && view.culled[i].cullSlot != Draw::kNotCulledOnGpu;
}

// The draws of the views `views` that are `caster`s, in the order they are recorded: fn(view, i,
// draw) for draw number i of `view`. Under GPU occlusion culling (`culled`) the culled draws
// (`culledDraws`: those alone, or the others).
template <typename Fn>
void forEachCasterDraw(const FrameScene& scene, const std::vector<uint32_t>& views, Caster caster,
                       const CulledDraws* culled, bool culledDraws, Fn&& fn) {
    for (uint32_t v : views) {
        const ShadowMapView& view = scene.shadows.views[v];
        for (size_t i = 0; i < view.draws.size(); ++i) {
            const Draw& draw = scene.draws[view.draws[i]];
            if (casterOf(draw) != caster || !casts(draw)) continue;
            if (culled && culledInView(view, i) != culledDraws) continue;
            fn(view, i, draw);
        }
    }
}

bool cullsBackFaces(const ShadowMapView& view, size_t i) { return !view.cullBackFaces.empty() && view.cullBackFaces[i]; }

// The pipeline the draws of one forEachCasterDraw call bind, by whether the draw culls back faces.
gpu::PipelineCache::Request shadowPipeline(const FrameScene& scene, Caster caster, const CulledDraws* culled,
                                           bool culledDraws, bool cullBackFaces) {
    const char* names[] = {"shadow_depth", "shadow_depth_cutout", "shadow_depth_spheres"};
    return gpu::PipelineCache::request<gpu::GraphicsPipelineDesc>(
        std::string(names[int(caster)]) + (culledDraws ? ".culled" : "") + (cullBackFaces ? ".backFacesCulled" : ""),
        [bindings = shadowBindings(scene.buffers, caster, culledDraws ? culled : nullptr), caster, culledDraws,
         cullBackFaces] { return describeShadowDepthPipeline(bindings, caster, culledDraws, cullBackFaces); });
}

// The casters and culled phases one raster pass records, in order: for a caster, its draws
// outside GPU culling (culledDraws false; none in the late pass, which draws the culled draws'
// late instances alone), then its culled draws.
template <typename Fn>
void forEachRecordedGroup(const CulledDraws* culled, Fn&& fn) {
    const bool late = culled && culled->phase == CulledDraws::Phase::Late;
    for (Caster caster : {Caster::Opaque, Caster::Cutout, Caster::Spheres}) {
        if (!late) fn(caster, false);
        if (culled) fn(caster, true);
    }
}

// Records the draws of every view in `views` that are `caster`s, each view into its tile.
void recordViews(VkCommandBuffer cmd, const gpu::PassResources& res, const FrameScene& scene,
                 const std::vector<uint32_t>& views, Caster caster, const CulledDraws* culled, bool culledDraws) {
    const std::vector<ShaderBinding> bindings = shadowBindings(scene.buffers, caster, culledDraws ? culled : nullptr);
    const gpu::Pipeline* bound = nullptr;
    const gpu::Pipeline* pipelines[2] = {nullptr, nullptr};  // by whether the draw culls back faces
    const ShadowMapView* inTile = nullptr;
    forEachCasterDraw(scene, views, caster, culled, culledDraws, [&](const ShadowMapView& view, size_t i, const Draw& draw) {
        const bool backFaces = cullsBackFaces(view, i);
        if (!pipelines[backFaces])
            pipelines[backFaces] = &res.pipelines().get(shadowPipeline(scene, caster, culled, culledDraws, backFaces));
        const gpu::Pipeline& pipeline = *pipelines[backFaces];
        if (&pipeline != bound) {
            bindBindings(cmd, pipeline, bindings, res);
            bound = &pipeline;
        }
        if (caster != Caster::Opaque) {
            const MaterialTextures& textures = scene.materialTextures[draw.textures];
            gpu::pushSampledImages(res.device(), cmd, pipeline,
                                   {{textures.samplers[kTextureOpacity], textures.images[kTextureOpacity]->view,
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}});
        }
        if (inTile != &view) {
            VkViewport viewport{float(view.x), float(view.y), float(view.size), float(view.size), 0.0f, 1.0f};
            VkRect2D tile{{int32_t(view.x), int32_t(view.y)}, {view.size, view.size}};
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &tile);
            inTile = &view;
        }
        DepthOnlyPush push{view.viewProjection, 0, kDepthBiasSlope};
        if (culledDraws) {
            const CulledViewDraw& c = view.culled[i];
            push.instanceIndex = culled->listOffset(c.firstCandidate);
            IndirectDraw indirect{res.buffer(culled->commands),
                                  VkDeviceSize(culled->command(c.cullSlot)) * sizeof(CulledDrawCommand)};
            recordDepthOnlyDraw(cmd, pipeline, draw, push, &indirect);
        } else {
            recordDepthOnlyDraw(cmd, pipeline, draw, push);
        }
    });
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

// The views to render this frame: every one without a history; with one, those whose key changed
// (the history takes their keys). `wholeAtlas`: the atlas holds nothing yet and is cleared whole.
std::vector<uint32_t> viewsToRender(const FrameScene& scene, ShadowAtlasHistory* history, bool& wholeAtlas) {
    const uint32_t viewCount = uint32_t(scene.shadows.views.size());
    std::vector<uint32_t> views;
    wholeAtlas = !history || !history->atlas.holdsContents();
    if (history && wholeAtlas) history->viewKeys.clear();
    if (history) history->viewKeys.resize(viewCount, 0);
    for (uint32_t v = 0; v < viewCount; ++v) {
        if (history) {
            const uint64_t key = viewKey(scene, scene.shadows.views[v]);
            if (!wholeAtlas && key == history->viewKeys[v]) continue;
            history->viewKeys[v] = key;
        }
        views.push_back(v);
    }
    return views;
}

// The atlas of this frame: a transient one without a history, the kept one with it.
gpu::ImageHandle atlasOf(gpu::FrameGraph& graph, const FrameScene& scene, ShadowAtlasHistory* history) {
    gpu::ImageDesc desc;
    desc.format = kShadowAtlasFormat;
    desc.width = scene.shadows.width;
    desc.height = scene.shadows.height;
    if (!history) return graph.createImage("shadowAtlas", desc);
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    return graph.importPersistent("shadowAtlas", history->atlas, desc);
}

// One raster pass over `render.views` of the atlas: the first clears their tiles (or the whole
// atlas), the late one draws over them.
gpu::ImageHandle addShadowRasterPass(gpu::FrameGraph& graph, const std::string& name, const FrameScene& scene,
                                     const ShadowMapRender& render, bool first, const CulledDraws* culled) {
    gpu::ImageHandle atlas = render.atlas;
    std::optional<CulledDraws> culledDraws;
    if (culled) culledDraws = *culled;
    graph.addPass(
        name, gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            forEachRecordedGroup(culled, [&](Caster caster, bool culledGroup) {
                bool used[2] = {false, false};  // by draws that keep and that cull back faces
                forEachCasterDraw(scene, render.views, caster, culled, culledGroup,
                                  [&](const ShadowMapView& view, size_t i, const Draw&) {
                                      used[cullsBackFaces(view, i)] = true;
                                  });
                for (bool cullBackFaces : {false, true})
                    if (used[cullBackFaces])
                        pass.usesPipeline(shadowPipeline(scene, caster, culled, culledGroup, cullBackFaces));
            });
            declareBindings(pass, shadowBindings(scene.buffers, Caster::Cutout, culled), ShaderStage::Graphics);
            if (culled) pass.read(culled->commands, gpu::Usage::IndirectCommandRead);
            // An empty view list leaves the atlas cleared to the far depth: nothing casts.
            atlas = first && render.wholeAtlas ? pass.depthStencilAttachment(atlas, VkClearDepthStencilValue{1.0f, 0})
                                               : pass.depthStencilAttachment(atlas);
        },
        [&scene, render, first, culledDraws](VkCommandBuffer cmd, const gpu::PassResources& res) {
            if (first && !render.wholeAtlas) clearTiles(cmd, scene, render.views);
            const CulledDraws* phase = culledDraws ? &*culledDraws : nullptr;
            forEachRecordedGroup(phase, [&](Caster caster, bool culledGroup) {
                recordViews(cmd, res, scene, render.views, caster, phase, culledGroup);
            });
        });
    return atlas;
}

}  // namespace

ShadowMapRender planShadowMaps(gpu::FrameGraph& graph, const FrameScene& scene, ShadowAtlasHistory* history) {
    ShadowMapRender render;
    render.atlas = atlasOf(graph, scene, history);
    render.views = viewsToRender(scene, history, render.wholeAtlas);
    render.rendered = !history || render.wholeAtlas || !render.views.empty();
    return render;
}

gpu::ImageHandle addShadowMapPass(gpu::FrameGraph& graph, const FrameScene& scene, ShadowAtlasHistory* history) {
    ShadowMapRender render = planShadowMaps(graph, scene, history);
    // Nothing changed: the kept atlas is read as it is, and no pass runs.
    if (!render.rendered) return render.atlas;
    return addShadowRasterPass(graph, "shadow_maps", scene, render, true, nullptr);
}

void addShadowMapEarlyPass(gpu::FrameGraph& graph, const FrameScene& scene, ShadowMapRender& render,
                           const CulledDraws& early) {
    render.atlas = addShadowRasterPass(graph, "shadow_maps", scene, render, true, &early);
}

gpu::ImageHandle addShadowMapLatePass(gpu::FrameGraph& graph, const FrameScene& scene, ShadowMapRender early,
                                      const CulledDraws& late) {
    return addShadowRasterPass(graph, "shadow_maps_late", scene, early, false, &late);
}

}  // namespace obscura::passes
