#include "renderer/frame_renderer.h"

#include "passes/accumulate.h"
#include "pass_support/best_fit_normals.h"
#include "passes/clip_volumes.h"
#include "passes/depth_of_field.h"
#include "passes/edge_aa.h"
#include "passes/motion_blur.h"
#include "passes/msaa_resolve.h"
#include "passes/transparent.h"
#include "renderer/reference_frames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

namespace obscura::renderer {
namespace {

// Reference mode's running sum, the size of the frame.
gpu::ImageDesc accumulationDesc(uint32_t width, uint32_t height) {
    gpu::ImageDesc desc;
    desc.format = passes::kAccumulationFormat;
    desc.width = width;
    desc.height = height;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    return desc;
}
// The light accumulation of the frames an integral is made of (a still's under SMAA 1TX, the
// reference's sub-frames): half floats. The small float format keeps 6 bits of mantissa (5 in blue) and
// lavapipe rounds towards zero, so every frame of a mean fell up to 1.6% short (a lit plane 0.3750
// and 0.3711 for the still and the reference where Lambert gives 0.3785).
constexpr passes::LightAccumulation kIntegralAccumulation = passes::LightAccumulation::HalfFloat;

}  // namespace

FrameRenderer::FrameRenderer(gpu::Device& device, VkSampler environmentSampler, LogSink log)
    : FrameRenderer(std::make_unique<gpu::DeviceFrameBackend>(device), nullptr, environmentSampler, std::move(log)) {}

FrameRenderer::FrameRenderer(gpu::FrameBackend& backend, VkSampler environmentSampler, LogSink log)
    : FrameRenderer(nullptr, &backend, environmentSampler, std::move(log)) {}

FrameRenderer::FrameRenderer(std::unique_ptr<gpu::FrameBackend> owned, gpu::FrameBackend* backend,
                             VkSampler environmentSampler, LogSink log)
    : ownedBackend_(std::move(owned)),
      backend_(backend ? *backend : *ownedBackend_),
      log_(std::move(log)),
      occlusion_(backend_),
      gpuOcclusion_(backend_) {
    bestFitNormals_ = passes::createBestFitNormalsTexture(backend_);
    // With SSAO off the lighting pass reads one unoccluded texel.
    const uint8_t open = 255;
    const float farDepth = 0.0f;
    gpu::ImageDesc one;
    one.width = one.height = 1;
    one.format = passes::kSsaoAccessibilityFormat;
    unoccluded_.accessibility = backend_.createTexture(one, &open, sizeof(open), "ssao off");
    one.format = passes::kSsaoDepthFormat;
    unoccluded_.halfDepth = backend_.createTexture(one, &farDepth, sizeof(farDepth), "ssao off depth");
    const uint16_t still[2] = {0xFBFF, 0};  // half floats: kStaticVelocity (-65504), 0
    static_assert(passes::kStaticVelocity == -65504.0f);
    one.format = passes::kVelocityFormat;
    stillVelocity_ = backend_.createTexture(one, still, sizeof(still), "still velocity");
    const uint8_t uncovered = 0;
    one.format = passes::kTransparentCoverageFormat;
    noTransparentCoverage_ = backend_.createTexture(one, &uncovered, sizeof(uncovered), "no transparent coverage");
    environment_ = std::make_unique<EnvironmentCache>(backend_, environmentSampler);
}

FrameRenderer::~FrameRenderer() { backend_.waitIdle(); }

std::string FrameRenderer::updateDisplay(const FrameSettings& settings) {
    passes::ColorLutRequest colour{settings.ocioConfig, settings.ocioDisplay, settings.ocioView, settings.ocioLook};
    if (std::string problem = gradingChart_.load(settings.gradingChart); !problem.empty())
        return "colour grading: " + problem;
    passes::DisplayGrade grade{gradingChart_.lattice(), settings.gradingInterpolation, gradingChart_.key()};
    if (std::string problem = grading_.update(backend_, colour, grade); !problem.empty())
        return "colour management: " + problem;
    return {};
}

void FrameRenderer::render(FrameSceneSource& source, const FrameRequest& request, const FrameSettings& settings) {
    const FrameCamera& camera = request.camera;
    const uint32_t width = camera.width, height = camera.height;
    // The `dof` setting turns the lens off for the post-process and the reference alike, and
    // `motionBlur` the shutter.
    const passes::ThinLens lens = settings.depthOfField ? camera.lens : passes::ThinLens{};
    std::array<double, 2> shutter{camera.time, camera.time};
    if (settings.motionBlur && camera.shutter[1] > camera.shutter[0]) shutter = camera.shutter;
    const uint32_t referenceSubFrames = settings.referenceSubFrames;
    FrameViewpoint viewpoint;
    if (referenceSubFrames > 0) accumulateReference(source, request, settings, lens, shutter);
    else if (shutter[1] > shutter[0]) viewpoint.shutter = shutter;

    // Temporal AA picks this frame's jitter before the scene's camera constants are packed. The
    // reference is its own ground truth, jittered per sub-frame: no temporal AA there.
    std::optional<TemporalAaStep> temporalAa;
    passes::TemporalAaSettings temporalAaSettings{settings.temporalAaMode, settings.temporalAaKLowFreq,
                                                  settings.temporalAaKHighFreq, settings.temporalAaReuseConverged};
    if (settings.temporalAa && referenceSubFrames == 0) {
        FrameView seen = source.view(viewpoint);
        // A still's sample resolves linearly; with MSAA under the box filter of width 1, over the
        // pixel's box.
        const bool pixelBox = settings.msaaSamples > 1 && isPixelBox(settings.pixelFilter);
        temporalAa = temporalAccumulation_.next({camera.key, width, height, request.settingsVersion},
                                                request.sceneVersion, temporalAaSettings.mode,
                                                settings.temporalAaFrames, seen.view, seen.projection,
                                                {viewpoint.shutter.has_value(), passes::hasDepthOfField(lens),
                                                 settings.pixelFilter, pixelBox ? settings.msaaSamples : 0u});
        viewpoint.clipJitter = temporalAa->clipJitter;
        if (temporalAa->shutterStratum) viewpoint.shutterSpan = *temporalAa->shutterStratum;
        if (temporalAa->lensStratum) {
            // The accumulation-buffer camera's lens, as the reference spreads its sub-frames.
            double apertureRadius = 0.5 * passes::accumulationApertureDiameter(lens);
            std::array<double, 2> onAperture =
                stillLensSample(*temporalAa->lensStratum, temporalAa->pass.framesToConverge, camera.aperture).position;
            viewpoint.lensOffset = {onAperture[0] * apertureRadius, onAperture[1] * apertureRadius};
        }
        viewpoint.noiseFrame = temporalAa->noiseFrame;
        if (temporalAa->stillSample) {
            viewpoint.sampleResolve = pixelBox ? passes::SampleResolve::PixelBox : passes::SampleResolve::Linear;
            viewpoint.meanSamples = temporalAa->pass.framesToConverge;
        }
        // Hybrid AA (seed 004) while anything changes; a still accumulates jittered frames of every
        // object, converging to the supersampled image, which edge AA never reaches.
        if (temporalAaSettings.mode == passes::TemporalAaMode::Smaa1tx && !temporalAa->pass.unchanged)
            viewpoint.edgeAaDistance = settings.hybridAaDistanceMetres / settings.metersPerUnit;
    } else {
        temporalAccumulation_.reset();
    }

    // Temporal AA reprojects what moved since the last frame along its own motion.
    InstanceModels models;
    if (temporalAa) {
        viewpoint.lastModels = &lastModels_;
        viewpoint.models = &models;
    }
    // Occlusion culling (seed 004): the last frame's coverage buffer, reprojected into this view,
    // or this frame's own depth on the GPU. The reference's sub-frames are not culled: each looks
    // from its own point of the lens.
    const bool culling = settings.occlusionCulling && referenceSubFrames == 0;
    viewpoint.gpuOcclusionCulling = culling && settings.occlusionCullingRoute == OcclusionCullingRoute::Gpu;
    const bool occlusionCulling = culling && !viewpoint.gpuOcclusionCulling;
    const CoverageKey coverageKey{camera.key, camera.time, request.drawnVersion, request.settingsVersion};
    CoverageView coverageView;
    std::optional<CoverageBuffer> coverage;
    if (occlusionCulling) {
        FrameView seen = source.view(viewpoint);
        coverageView = {seen.view, multiply(seen.projection, viewpoint.clipJitter), width, height};
        coverage = occlusion_.reproject(coverageKey, coverageView);
        viewpoint.occlusion = coverage ? &*coverage : nullptr;
    }
    passes::FrameScene scene = source.scene(viewpoint);
    lastModels_ = std::move(models);

    // The frame (DESIGN.md "The frame"): shadow maps, G-buffer, clip volumes into stencil, SSAO,
    // lighting, temporal AA, depth of field, tone mapping, AOV readback. In reference mode the
    // accumulated sub-frames replace all between the G-buffer and tone mapping; the other AOVs come
    // from the pinhole camera.
    // With msaa > 1 the G-buffer is multisampled and the custom resolve hands the single-sample
    // one to everything after it; the lighting pass alone reads the samples (seed 000 "Deferred
    // MSAA"). Reference mode's sub-frames (accumulateReference) jitter on their own; its frame
    // here renders one sample.
    gpu::FrameGraph graph;
    passes::importSceneBuffers(graph, scene);
    gpu::ImageHandle shadowAtlas;
    const GpuOcclusionCulling::Versions versions{request.drawnVersion, request.settingsVersion};
    if (referenceSubFrames == 0)
        shadowAtlas = scene.shadows.gpuCulledDraws > 0
                          ? gpuOcclusion_.addShadowMaps(graph, scene, versions, shadowHistory_)
                          : passes::addShadowMapPass(graph, scene, &shadowHistory_);
    auto samples = VkSampleCountFlagBits(referenceSubFrames == 0 ? settings.msaaSamples : 1u);
    const gpu::ImageHandle bestFitNormals = graph.importTexture("bestFitNormals", bestFitNormals_);
    passes::GBuffer gbuffer =
        scene.gpuCulledDraws > 0
            ? gpuOcclusion_.addGBuffer(graph, scene, versions, bestFitNormals, samples, settings.msaaAlphaToCoverage)
            : passes::addGBufferPass(graph, scene, bestFitNormals, samples, settings.msaaAlphaToCoverage);
    std::optional<MsaaFrame> msaa;
    if (samples != VK_SAMPLE_COUNT_1_BIT) msaa = addMsaaResolve(graph, scene, gbuffer);
    // The next frame's coverage buffer, from the opaque depth (with MSAA the farthest sample's).
    // Where an instance moves within the shutter, a still's frames see it at other times; hybrid
    // AA's instances are drawn without the jitter the reprojection assumes: such depth would not
    // stand for the next frame.
    const bool anyMoving = std::any_of(scene.draws.begin(), scene.draws.end(),
                                       [](const passes::Draw& d) { return d.moving || d.shutterPositions; });
    if (occlusionCulling && !anyMoving && !scene.edgeAa)
        occlusion_.addToFrame(graph, msaa ? msaa->maxDepth : gbuffer.depth, coverageKey, coverageView);
    gpu::ImageHandle hdr;
    gpu::ImageHandle transparentCoverage;
    bool dofAfterTemporalAa = false;
    if (referenceSubFrames > 0) {
        gpu::ImageHandle sum =
            graph.importPersistent("referenceAccumulation", accumulation_, accumulationDesc(width, height));
        hdr = passes::addAccumulationResolvePass(graph, sum, VK_FORMAT_R16G16B16A16_SFLOAT);
        // The sub-frames blended the transparent surfaces into the accumulation. XXX: the alpha of
        // the reference's colour is the pinhole G-buffer's coverage alone (no transparent
        // coverage): transparents over the background are not in it.
        transparentCoverage = graph.importTexture("transparentCoverage.none", noTransparentCoverage_);
    } else {
        // Any frame of SMAA 1TX may start or join a still's mean (and a frame of change must match
        // the still it interrupts where nothing changed).
        const bool stillFrame = temporalAa && temporalAaSettings.mode == passes::TemporalAaMode::Smaa1tx;
        hdr = addLighting(graph, scene, gbuffer, shadowAtlas, source.view(viewpoint), request, settings,
                          stillFrame ? kIntegralAccumulation : settings.lightAccumulation,
                          transparentCoverage, msaa ? &*msaa : nullptr);
        // A still's sample of the shutter is blurred over its stratum alone, before it joins the
        // mean: the post-process fills only what lies between the samples' times.
        const bool stratumBlur = scene.motionBlur && temporalAa && temporalAa->shutterStratum;
        // A still's sample of the lens likewise is blurred over its cell of the aperture alone.
        const bool lensSample = temporalAa && temporalAa->lensStratum;
        auto depthOfField = [&](const passes::ApertureCell& cell, std::array<double, 2> jitter) {
            passes::CocFromDepth coc =
                passes::cocFromDepth(lens, camera.clippingRange[0], camera.clippingRange[1], double(width));
            // A still's sample spreads over its own cell alone: at full resolution (FieldResolution).
            passes::FieldResolution resolution = cell.share() < 1.0 ? passes::FieldResolution::Full
                                                                     : passes::FieldResolution::Half;
            return passes::DepthOfFieldSettings{coc, camera.aperture, cell, jitter, settings.depthOfFieldTaps,
                                                resolution};
        };
        if (stratumBlur || lensSample) {
            hdr = passes::addTemporalAaSamplePass(graph, scene, gbuffer, hdr, transparentCoverage);
            if (lensSample)
                hdr = passes::addDepthOfFieldPasses(
                    graph, scene, gbuffer, hdr,
                    depthOfField(stillLensSample(*temporalAa->lensStratum, temporalAa->pass.framesToConverge,
                                                 camera.aperture).cell,
                                 temporalAa->jitter));
            if (stratumBlur)
                hdr = passes::addMotionBlurPasses(graph, scene, gbuffer, hdr, settings.motionBlurSamples);
            temporalAa->pass.colorHasCoverage = true;
        }
        if (temporalAa) {
            temporalAa->pass.edgeAa = scene.edgeAa;
            hdr = passes::addTemporalAaPass(graph, scene, gbuffer, hdr, transparentCoverage, temporalAaSettings,
                                            temporalAa->pass, temporalAaHistory_);
            if (scene.edgeAa) hdr = passes::addEdgeAaPasses(graph, scene, gbuffer, hdr);
        }
        // Over the whole aperture, unless the still's mean holds it, sample by sample.
        dofAfterTemporalAa = passes::hasDepthOfField(lens) && !lensSample && !(temporalAa && temporalAa->lensAccumulated);
        if (dofAfterTemporalAa)
            hdr = passes::addDepthOfFieldPasses(graph, scene, gbuffer, hdr, depthOfField({}, {}));
        // After depth of field (seed 000 "MB or DOF first?": motion blur gathers with the
        // geometry's depth and velocity, and is the error less seen when it comes last), over the
        // whole shutter: unless the still's mean already holds it, sample by sample.
        if (scene.motionBlur && !stratumBlur && !(temporalAa && temporalAa->shutterAccumulated))
            hdr = passes::addMotionBlurPasses(graph, scene, gbuffer, hdr, settings.motionBlurSamples);
    }
    // Temporal AA's accumulation carries coverage in alpha, and motion blur blurs it along; depth of
    // field keeps a sample's coverage where it runs before the mean, and writes none after it.
    passes::HdrAlpha hdrAlpha = passes::HdrAlpha::None;
    if (temporalAa && !dofAfterTemporalAa) hdrAlpha = passes::HdrAlpha::Coverage;
    gpu::ImageHandle velocity =
        gbuffer.velocity.valid()
            ? gbuffer.velocity
            : graph.importTexture("velocity.still", stillVelocity_);
    passes::addAovReadbackPass(graph, scene, gbuffer, hdr, hdrAlpha, transparentCoverage, grading_, velocity,
                               request.aovs);
    executeFrame(graph);
    occlusion_.frameDone();
    if (scene.gpuCulledDraws > 0) {
        GpuOcclusionCulling::Culled culled = gpuOcclusion_.culled(scene);
        source.culledOnGpu(culled.draws, culled.instances, culled.triangles);
    }
    converged_ = !temporalAa || temporalAa->converged;
    if (msaa) {
        // Issue 5: the share of pixels the per-sample mask sends to sample-frequency lighting.
        uint32_t tagged = *static_cast<const uint32_t*>(msaaTaggedPixels_->mapped());
        char line[160];
        std::snprintf(line, sizeof(line), "msaa %ux: %.2f%% of pixels tagged for per-sample lighting (%u of %u)",
                      uint32_t(samples), 100.0 * tagged / (double(width) * height), tagged, width * height);
        log_(LogLevel::Info, line);
    }
}

FrameRenderer::MsaaFrame FrameRenderer::addMsaaResolve(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                                       passes::GBuffer& gbuffer) {
    if (!msaaTaggedPixels_)
        msaaTaggedPixels_ = backend_.createBuffer(sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                  gpu::MemoryUsage::Readback, "msaa tagged pixels");
    *static_cast<uint32_t*>(msaaTaggedPixels_->mapped()) = 0;
    passes::PerSampleLighting perSample{gbuffer, graph.importBuffer("msaaTaggedPixels", msaaTaggedPixels_)};
    graph.markOutput(perSample.taggedPixelCount);
    passes::MsaaResolve resolve = passes::addMsaaResolvePass(graph, scene, gbuffer);
    gbuffer = resolve.resolved;
    return {perSample, resolve.maxDepth};
}

gpu::ImageHandle FrameRenderer::addLighting(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                            passes::GBuffer& gbuffer, gpu::ImageHandle shadowAtlas,
                                            const FrameView& seen, const FrameRequest& request,
                                            const FrameSettings& settings, passes::LightAccumulation accumulation,
                                            gpu::ImageHandle& transparentCoverage, const MsaaFrame* msaa) {
    gbuffer.depth = passes::addClipVolumePass(graph, scene, gbuffer.depth);
    passes::SsaoResult ambient;
    if (settings.ssao) {
        // The radius is authored in metres; the passes work in scene units (USD metersPerUnit).
        passes::SsaoSettings ssao{float(settings.ssaoRadiusMetres / settings.metersPerUnit),
                                  float(settings.ssaoIntensity)};
        // The history reprojects through the camera's motion; anything else that changes what a
        // texel means (size, projection, settings) restarts it.
        auto& last = ssaoHistoryFrame_;
        ssaoHistory_.valid = last.valid && last.width == scene.width && last.height == scene.height &&
                             last.projection == seen.projection && last.settingsVersion == request.settingsVersion;
        Matrix4d inverseView = kIdentity;
        invert(seen.view, inverseView);
        ssaoHistory_.viewToPreviousView = toFloats<passes::Mat4>(multiply(inverseView, last.view));
        ambient = passes::addSsaoPasses(graph, scene, gbuffer, ssao, ssaoHistory_);
    } else {
        ambient = {graph.importTexture("ssao.off", unoccluded_.accessibility),
                   graph.importTexture("ssao.off.depth", unoccluded_.halfDepth)};
    }
    ssaoHistoryFrame_ = {settings.ssao, seen.view, seen.projection, scene.width, scene.height, request.settingsVersion};
    passes::EnvironmentLighting environment = environment_->addToFrame(graph, request.environment);
    gpu::ImageHandle hdr = passes::addLightingPass(graph, scene, gbuffer, ambient, shadowAtlas, environment,
                                                   accumulation, msaa ? &msaa->perSample : nullptr);
    // Transparent surfaces over the lit opaque ones, before temporal AA (DESIGN.md "The frame").
    if (scene.transparentDraws.empty()) {
        transparentCoverage = graph.importTexture("transparentCoverage.none", noTransparentCoverage_);
        return hdr;
    }
    // The fade distance is authored in metres, like the SSAO radius.
    passes::TransparentSettings transparents{float(settings.transparentFadeMetres / settings.metersPerUnit)};
    passes::TransparentResult transparent =
        passes::addTransparentPass(graph, scene, scene.transparentDraws, msaa ? msaa->maxDepth : gbuffer.depth, hdr,
                                   shadowAtlas, environment, transparents);
    transparentCoverage = transparent.coverage;
    return transparent.hdr;
}

void FrameRenderer::executeFrame(gpu::FrameGraph& graph) {
    backend_.run(graph);
    timings_ = backend_.timings();
    // The transient images' memory, when another frame places them otherwise.
    const gpu::TransientMemory& memory = graph.transientMemory();
    if (memory.bytes() != transientBytes_) {
        transientBytes_ = memory.bytes();
        char line[160];
        std::snprintf(line, sizeof(line), "transient images: %zu in %.1f MiB (%.1f MiB without aliasing)",
                      memory.placements.size(), double(memory.bytes()) / (1 << 20),
                      double(memory.unaliasedBytes()) / (1 << 20));
        log_(LogLevel::Info, line);
    }
}

void FrameRenderer::accumulateReference(FrameSceneSource& source, const FrameRequest& request,
                                        const FrameSettings& settings, const passes::ThinLens& lens,
                                        const std::array<double, 2>& shutter) {
    const uint32_t width = request.camera.width, height = request.camera.height;
    const gpu::ImageDesc sumDesc = accumulationDesc(width, height);
    // Without depth of field the lens is a pinhole: every sub-frame looks from its centre.
    bool lensBlur = passes::hasDepthOfField(lens);
    double apertureRadius = 0.5 * passes::accumulationApertureDiameter(lens);
    const double open = shutter[0], close = shutter[1];
    const passes::ApertureShape aperture = lensBlur ? request.camera.aperture : passes::ApertureShape{};
    uint32_t samples = referenceSamples(settings.pixelFilter);
    std::vector<ReferenceSubFrame> subFrames =
        referenceSubFrames(settings.referenceSubFrames, aperture, settings.pixelFilter, samples);
    auto sceneOf = [&](const ReferenceSubFrame& sub) {
        FrameViewpoint viewpoint;
        viewpoint.meanSamples = uint32_t(subFrames.size());
        if (close > open) viewpoint.shutter = shutter;
        std::array<double, 2> jitter = sub.pixelJitter;
        if (samples > 1) {
            // The samples resolve over the pixel's box (as a still's do), which the lighting pass
            // finds through the frame's clip-space jitter; an edge pixel's box takes samples from
            // the guard pixels beyond it.
            viewpoint.guardPixels = 1;
            viewpoint.clipJitter[12] = 2.0 * jitter[0] / (width + 2);
            viewpoint.clipJitter[13] = 2.0 * jitter[1] / (height + 2);
            viewpoint.sampleResolve = passes::SampleResolve::PixelBox;
            jitter = {0.0, 0.0};
        }
        viewpoint.sample = FrameSample{open + sub.shutter * (close - open),
                                       {sub.aperture[0] * apertureRadius, sub.aperture[1] * apertureRadius},
                                       jitter, sub.emitter};
        return std::pair{viewpoint, source.scene(viewpoint)};
    };
    for (size_t k = 0; k < subFrames.size(); ++k) {
        auto [viewpoint, scene] = sceneOf(subFrames[k]);
        // Transparent surfaces blend at pixel frequency over the farthest of a pixel's samples
        // (passes/transparent.h), which is exact with one sample alone.
        if (k == 0 && samples > 1 && !scene.transparentDraws.empty()) {
            samples = 1;
            subFrames = referenceSubFrames(settings.referenceSubFrames, aperture, settings.pixelFilter, samples);
            std::tie(viewpoint, scene) = sceneOf(subFrames[k]);
        }
        gpu::FrameGraph graph;
        passes::importSceneBuffers(graph, scene);
        gpu::ImageHandle shadowAtlas = passes::addShadowMapPass(graph, scene);
        passes::GBuffer gbuffer = passes::addGBufferPass(graph, scene, graph.importTexture("bestFitNormals", bestFitNormals_),
                                                         VkSampleCountFlagBits(samples));
        std::optional<MsaaFrame> msaa;
        if (samples > 1) msaa = addMsaaResolve(graph, scene, gbuffer);
        // Each sub-frame blends its transparent surfaces into its lighting; their coverage is not kept.
        gpu::ImageHandle transparentCoverage;
        gpu::ImageHandle hdr = addLighting(graph, scene, gbuffer, shadowAtlas, source.view(viewpoint), request,
                                           settings, kIntegralAccumulation, transparentCoverage, msaa ? &*msaa : nullptr);
        gpu::ImageHandle sum = graph.importPersistent("referenceAccumulation", accumulation_, sumDesc);
        passes::addAccumulatePass(graph, hdr, sum, 1.0f, k == 0, viewpoint.guardPixels);
        executeFrame(graph);
    }
}

}  // namespace obscura::renderer
