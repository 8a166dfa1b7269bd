#include "passes/gbuffer.h"

#include "generated/shader_layouts.h"
#include "passes/frame_data.h"
#include "passes/material_draw.h"
#include "passes/shader_pass.h"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <tuple>

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

// How a draw's fragments make its surface: opaque (the depth test runs before shading), cut out by
// its material's opacity threshold, or sphere impostors (the sphere each cube bounds, its depth
// written by the shader; a cut-out material cuts them too).
enum class Surface { Opaque, Spheres, Cutout };

Surface surfaceOf(const Draw& draw) {
    if (draw.sphereImpostors) return Surface::Spheres;
    return draw.opacityCutout ? Surface::Cutout : Surface::Opaque;
}

const char* surfaceName(Surface surface) {
    switch (surface) {
        case Surface::Opaque: return "";
        case Surface::Spheres: return "spheres.";
        case Surface::Cutout: return "cutout.";
    }
    return "";
}

// Set 0: the camera, the records, the best-fit normal table and the lights (the principal lobe of
// anisotropic materials), and for variants that move the instances' motion, or for draws culled on
// the GPU the records the culling pass left them.
std::vector<ShaderBinding> gbufferBindings(bool motion, const SceneBuffers& buffers, gpu::ImageHandle bestFitNormals,
                                           const CulledDraws* culled = nullptr) {
    std::vector<ShaderBinding> bindings{bufferRead(buffers.camera), bufferRead(buffers.instances),
                                        bufferRead(buffers.materials), sampled(bestFitNormals),
                                        bufferRead(buffers.lights)};
    if (motion) bindings.push_back(bufferRead(buffers.instanceMotions));
    else if (culled) bindings.push_back(bufferRead(culled->lists));
    return bindings;
}

// Opaque surfaces take the shaders' OPAQUE_SURFACE variant, whose depth test runs before shading,
// sphere impostors their SPHERE_IMPOSTOR one (common/gbuffer_surface.glsl). `culled`: the draw's
// records come from GPU occlusion culling's list (a static variant only).
gpu::GraphicsPipelineDesc describeGBufferPipeline(Variant variant, Surface surface, bool culled, bool cullBackFaces,
                                                  VkSampleCountFlagBits samples, bool perSample, bool emissionTarget,
                                                  uint32_t features, const std::vector<ShaderBinding>& bindings) {
    const std::vector<gpu::SpecializationConstant> specialization{{kMaterialFeaturesConstant, features}};
    gpu::GraphicsPipelineDesc d;
    d.specialization = specialization;
    if (cullBackFaces) d.cullMode = VK_CULL_MODE_BACK_BIT;
    d.fragmentShader = std::string(writesVelocity(variant) ? "gbuffer_moving" : "gbuffer") +
                       (surface == Surface::Opaque ? "_opaque" : surface == Surface::Spheres ? "_spheres" : "") +
                       (perSample ? "_per_sample.frag" : ".frag");
    d.sampleShading = perSample;
    d.bindings = bindingLayout(bindings);
    d.pushedSamplers = kMaterialTextureSlots;  // set 1: the draw's material textures
    d.pushConstantSize = sizeof(GBufferPush);
    setSceneVertexInput(d);
    if (culled) d.vertexShader = "gbuffer_culled.vert";
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
    // RT4, written by the draws whose materials' emission is textured; without a velocity target,
    // RT3 is an unused slot.
    if (emissionTarget) {
        if (d.colorFormats.size() == 3) {
            d.colorFormats.push_back(VK_FORMAT_UNDEFINED);
            d.untouchedColorAttachments |= 1u << 3;
        }
        d.colorFormats.push_back(kEmissionFormat);
        if ((features & kMaterialTexturedEmission) == 0u) d.untouchedColorAttachments |= 1u << 4;
    }
    d.depthFormat = gbufferDepthFormat(samples);
    d.samples = samples;
    return d;
}

struct Ordered {
    Variant variant;
    const Draw* draw;
};

Variant variantOf(const Draw& draw, bool velocityTarget) {
    if (draw.shutterPositions) return velocityTarget ? Variant::Deforming : Variant::DeformingWithoutVelocity;
    if (!velocityTarget) return Variant::Static;
    return draw.moving ? Variant::Moving : Variant::StaticWithVelocityTarget;
}

// The draws of one raster pass, grouped by pipeline. Moving geometry is drawn last (seed 000 "An
// improved reconstruction filter (3)"), so static surfaces never cover a velocity a moving one
// wrote. Within a variant, opaque draws come first: what they hide is then never shaded; draws
// whose materials use the same features (the pipeline's specialization) follow each other.
// Under GPU occlusion culling (`culled`) the early pass draws the static variants (the culled
// draws' early instances among them) and the late pass the culled draws' late instances, then
// the moving variants.
std::vector<Ordered> orderedDraws(const FrameScene& scene, const CulledDraws* culled) {
    std::vector<Ordered> ordered;
    for (Variant variant : {Variant::Static, Variant::StaticWithVelocityTarget, Variant::DeformingWithoutVelocity,
                            Variant::Moving, Variant::Deforming}) {
        const bool lastVariants = variant == Variant::Moving || variant == Variant::Deforming;
        for (Surface surface : {Surface::Opaque, Surface::Spheres, Surface::Cutout}) {
            const size_t first = ordered.size();
            for (const Draw& draw : scene.cameraDraws) {
                // Transparent surfaces are drawn after lighting (passes/transparent.h).
                if (draw.transparent || surfaceOf(draw) != surface || variantOf(draw, scene.motionBlur) != variant)
                    continue;
                if (culled && culled->phase == CulledDraws::Phase::Early && lastVariants) continue;
                if (culled && culled->phase == CulledDraws::Phase::Late && !lastVariants && !draw.culledOnGpu())
                    continue;
                ordered.push_back({variant, &draw});
            }
            std::stable_sort(ordered.begin() + std::ptrdiff_t(first), ordered.end(), [](const Ordered& a, const Ordered& b) {
                return a.draw->materialFeatures < b.draw->materialFeatures;
            });
        }
    }
    return ordered;
}

// Ordered draws that bind one pipeline, and its bindings: the runs of a pass's draws, up to `end`.
struct PipelineRun {
    size_t end;
    gpu::PipelineCache::Request pipeline;
    std::vector<ShaderBinding> bindings;
};

std::vector<PipelineRun> pipelineRuns(const std::vector<Ordered>& ordered, const FrameScene& scene,
                                      const std::optional<CulledDraws>& culled, gpu::ImageHandle bestFitNormals,
                                      VkSampleCountFlagBits samples, bool emissionTarget) {
    // MSAA samples resolved over the pixel's box (a still's frames, the reference's sub-frames:
    // SampleResolve::PixelBox) are shaded each at its own position (common/gbuffer_surface.glsl
    // PER_SAMPLE_SHADING) where the device can; sphere impostors find their samples' hits
    // themselves and stay per pixel.
    const bool pixelBoxSamples =
        samples > VK_SAMPLE_COUNT_1_BIT && scene.cameraData.sampleResolve == uint32_t(SampleResolve::PixelBox);
    std::vector<PipelineRun> runs;
    std::tuple<Variant, Surface, bool, bool, uint32_t> bound{};
    for (size_t i = 0; i < ordered.size(); ++i) {
        const Ordered& o = ordered[i];
        const Surface surface = surfaceOf(*o.draw);
        const bool culledDraw = culled && o.draw->culledOnGpu();
        const bool backFaces = o.draw->cullBackFaces;
        const uint32_t features = o.draw->materialFeatures;
        const auto state = std::tuple(o.variant, surface, culledDraw, backFaces, features);
        if (!runs.empty() && state == bound) {
            runs.back().end = i + 1;
            continue;
        }
        bound = state;
        std::vector<ShaderBinding> bindings =
            gbufferBindings(readsMotion(o.variant), scene.buffers, bestFitNormals, culledDraw ? &*culled : nullptr);
        const bool perSample = pixelBoxSamples && surface != Surface::Spheres;
        std::string name = std::string(pipelineName(o.variant)) + "." + surfaceName(surface) +
                           (culledDraw ? "culled." : "") + (backFaces ? "backFacesCulled." : "") +
                           (perSample ? "perSample." : "") + (emissionTarget ? "emission." : "") +
                           std::to_string(samples) + gpu::specializationSuffix({{kMaterialFeaturesConstant, features}});
        auto build = [=, variant = o.variant](gpu::Device& device) {
            const bool sampleShading = perSample && device.context().enabledFeatures().sampleRateShading;
            return std::make_unique<gpu::Pipeline>(
                device, describeGBufferPipeline(variant, surface, culledDraw, backFaces, samples, sampleShading,
                                                emissionTarget, features, bindings));
        };
        runs.push_back({i + 1, {std::move(name), std::move(build)}, std::move(bindings)});
    }
    return runs;
}

// One raster pass of the G-buffer over `gb`: cleared first, or (the late pass) drawn over.
GBuffer addGBufferRasterPass(gpu::FrameGraph& graph, const std::string& name, const FrameScene& scene, GBuffer gb,
                             bool clear, gpu::ImageHandle bestFitNormals, VkSampleCountFlagBits samples,
                             bool alphaToCoverage, const CulledDraws* culled) {
    const std::vector<Ordered> ordered = orderedDraws(scene, culled);
    const bool anyMotion =
        std::any_of(ordered.begin(), ordered.end(), [](const Ordered& o) { return readsMotion(o.variant); });
    std::optional<CulledDraws> culledDraws;
    if (culled) culledDraws = *culled;
    const std::vector<PipelineRun> runs =
        pipelineRuns(ordered, scene, culledDraws, bestFitNormals, samples, gb.emission.valid());

    graph.addPass(
        name, gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            for (const PipelineRun& run : runs) pass.usesPipeline(run.pipeline);
            declareBindings(pass, gbufferBindings(anyMotion, scene.buffers, bestFitNormals), ShaderStage::Graphics);
            if (culled) {
                declareBindings(pass, {bufferRead(culled->lists)}, ShaderStage::Graphics);
                pass.read(culled->commands, gpu::Usage::IndirectCommandRead);
            }
            using Load = gpu::FrameGraph::PassBuilder::Load;
            if (clear) {
                gb.depth = pass.depthStencilAttachment(gb.depth, VkClearDepthStencilValue{1.0f, 0});
                gb.normalRoughness =
                    pass.colorAttachment(gb.normalRoughness, VkClearColorValue{{0.5f, 0.5f, 1.0f, 1.0f}});
                gb.albedoMetallic =
                    pass.colorAttachment(gb.albedoMetallic, VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}});
                gb.instance = pass.colorAttachment(gb.instance, VkClearColorValue{.uint32 = {0, 0, 0, 0}});
                if (gb.velocity.valid())
                    gb.velocity =
                        pass.colorAttachment(gb.velocity, VkClearColorValue{{kStaticVelocity, 0.0f, 0.0f, 0.0f}});
                if (gb.emission.valid()) {
                    if (!gb.velocity.valid()) pass.unusedColorAttachment();
                    gb.emission = pass.colorAttachment(gb.emission, VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}});
                }
            } else {
                gb.depth = pass.depthStencilAttachment(gb.depth, Load::Keep);
                gb.normalRoughness = pass.colorAttachment(gb.normalRoughness, Load::Keep);
                gb.albedoMetallic = pass.colorAttachment(gb.albedoMetallic, Load::Keep);
                gb.instance = pass.colorAttachment(gb.instance, Load::Keep);
                if (gb.velocity.valid()) gb.velocity = pass.colorAttachment(gb.velocity, Load::Keep);
                if (gb.emission.valid()) {
                    if (!gb.velocity.valid()) pass.unusedColorAttachment();
                    gb.emission = pass.colorAttachment(gb.emission, Load::Keep);
                }
            }
        },
        [ordered, runs, &scene, samples, alphaToCoverage, culledDraws](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::Device& device = res.device();
            size_t first = 0;
            for (const PipelineRun& run : runs) {
                const gpu::Pipeline& pipeline = res.pipelines().get(run.pipeline);
                bindBindings(cmd, pipeline, run.bindings, res);
                const MaterialTextures* pushed = nullptr;  // a new layout: the pushed set starts over
                for (size_t i = first; i < run.end; ++i) {
                    const Draw& draw = *ordered[i].draw;
                    if (culledDraws && draw.culledOnGpu()) {
                        // The draw's records from its list; its instance count from the culling pass.
                        GBufferPush push{culledDraws->listOffset(draw.firstCandidate), uint32_t(samples),
                                         alphaToCoverage ? 1u : 0u};
                        IndirectDraw indirect{res.buffer(culledDraws->commands),
                                              VkDeviceSize(culledDraws->command(draw.cullSlot)) *
                                                  sizeof(CulledDrawCommand)};
                        recordMaterialDraw(device, cmd, pipeline, scene, draw, pushed, &push, sizeof(push), &indirect);
                    } else {
                        GBufferPush push{draw.instanceIndex, uint32_t(samples), alphaToCoverage ? 1u : 0u};
                        recordMaterialDraw(device, cmd, pipeline, scene, draw, pushed, &push, sizeof(push));
                    }
                }
                first = run.end;
            }
        });
    return gb;
}

}  // namespace

GBuffer addGBufferPass(gpu::FrameGraph& graph, const FrameScene& scene, gpu::ImageHandle bestFitNormals,
                       VkSampleCountFlagBits samples, bool alphaToCoverage, const CulledDraws* early) {
    GBuffer gb = createGBufferImages(graph, scene, samples, "gbuffer");
    return addGBufferRasterPass(graph, "gbuffer", scene, gb, true, bestFitNormals, samples, alphaToCoverage, early);
}

GBuffer addGBufferLatePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& early,
                           gpu::ImageHandle bestFitNormals, VkSampleCountFlagBits samples, bool alphaToCoverage,
                           const CulledDraws& late) {
    return addGBufferRasterPass(graph, "gbuffer_late", scene, early, false, bestFitNormals, samples, alphaToCoverage,
                                &late);
}

}  // namespace obscura::passes
