// Whole frames wired by the renderer (renderer/frame_renderer.cpp) for several settings, run
// against a mock backend without a GPU: which passes run, in which order, which are culled, and
// which barriers the frame graph derives between them.
#include "renderer/frame_renderer.h"
#include "tests/unit/mock_frame_backend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace obscura::renderer {
namespace {

using Frame = test::MockFrameBackend::Frame;

constexpr uint32_t kWidth = 64, kHeight = 36;

// One opaque and one transparent draw (unless `glass` is off); with motion blur the opaque one
// moves. Records are empty host buffers: nothing is drawn, but every pass that reads them declares
// them.
class SceneOfTwoDraws final : public FrameSceneSource {
public:
    explicit SceneOfTwoDraws(gpu::FrameBackend& backend) : backend_(backend) {}

    FrameView view(const FrameViewpoint&) const override { return {kIdentity, kIdentity}; }
    void culledOnGpu(uint32_t, uint64_t, uint64_t) override {}

    passes::FrameScene scene(const FrameViewpoint& viewpoint) override {
        passes::FrameScene s;
        s.width = kWidth;
        s.height = kHeight;
        auto records = [&](const char* name) { return backend_.createBuffer(256, 0, gpu::MemoryUsage::Upload, name); };
        s.camera = records("camera");
        s.instances = records("instances");
        s.instanceMotions = records("instance motions");
        s.instanceReprojections = records("instance reprojections");
        s.materials = records("materials");
        s.lights = records("lights");
        s.environment = records("environment");
        s.shadows.records = records("shadow views");
        s.materialTextures.resize(1);
        // A real-time frame with an open shutter samples it; a reference sub-frame is an instant.
        s.motionBlur = viewpoint.shutter.has_value() && !viewpoint.sample;
        passes::Draw opaque;
        opaque.vertices = records("vertices");
        opaque.indices = records("indices");
        opaque.indexCount = 3;
        opaque.moving = s.motionBlur;
        passes::Draw glass = opaque;
        glass.moving = false;
        glass.transparent = true;
        glass.instanceIndex = 1;
        s.draws = {opaque, glass};
        if (!withGlass) s.draws.pop_back();
        s.cameraDraws = {opaque};
        // Occlusion culling on the GPU: the still opaque draw's one instance is a candidate.
        if (viewpoint.gpuOcclusionCulling && !opaque.moving) {
            s.cameraDraws.front().cullSlot = 0;
            s.gpuCulledDraws = 1;
            s.occlusionCandidates = records("occlusion candidates");
            s.occlusionCandidateCount = 1;
        }
        if (withGlass) s.transparentDraws = {1};
        if (withClipVolume) s.clipVolumes = {{opaque, 0x01}};
        s.instanceCount = uint32_t(s.draws.size());
        s.edgeAa = viewpoint.edgeAaDistance > 0.0;
        return s;
    }

    bool withGlass = true;
    bool withClipVolume = false;

private:
    gpu::FrameBackend& backend_;
};

// A renderer on the mock, its scene and one frame's request; render() runs one frame.
struct Wiring {
    test::MockFrameBackend backend;
    FrameRenderer renderer{backend, VK_NULL_HANDLE, [](LogLevel, const std::string&) {}};
    SceneOfTwoDraws source{backend};
    FrameSettings settings;
    FrameRequest request;

    Wiring() {
        request.camera.key = "/Camera";
        request.camera.width = kWidth;
        request.camera.height = kHeight;
        request.camera.clippingRange = {0.1, 100.0};
        request.aovs.push_back({passes::Aov::Color,
                                backend.createBuffer(kWidth * kHeight * 16, 0, gpu::MemoryUsage::Readback, "color"),
                                nullptr});
    }
    // A lens that blurs: 50 mm at f/2 focused at 2 m, on a 36 mm film.
    void openLens() { request.camera.lens = {0.05, 2.0, 2.0, 0.036}; }
    void openShutter() { request.camera.shutter = {-0.25, 0.25}; }
    const Frame& render() {
        EXPECT_EQ(renderer.updateDisplay(settings), "");
        size_t before = backend.frames.size();
        renderer.render(source, request, settings);
        EXPECT_GT(backend.frames.size(), before);
        return backend.frames.back();
    }
};

std::vector<std::string> passesThat(const Frame& frame, bool culled) {
    std::vector<std::string> names;
    for (const auto& pass : frame.passes)
        if (pass.culled == culled) names.push_back(pass.name);
    return names;
}
std::vector<std::string> running(const Frame& frame) { return passesThat(frame, false); }

// The barrier a pass waits at before it touches `image`.
const gpu::PlannedBarrier* barrier(const Frame& frame, const std::string& pass, const std::string& image) {
    for (const auto& p : frame.passes)
        if (p.name == pass && !p.culled)
            for (const auto& b : p.barriers)
                if (b.isImage && frame.imageNames[b.resource] == image) return &b;
    return nullptr;
}

// The barrier before `pass` touches `image`, expected to take it from layout `from` to `to`.
const gpu::PlannedBarrier* transition(const Frame& frame, const std::string& pass, const std::string& image,
                                      VkImageLayout from, VkImageLayout to) {
    const gpu::PlannedBarrier* b = barrier(frame, pass, image);
    EXPECT_NE(b, nullptr) << pass << " does not wait for " << image;
    if (!b) return nullptr;
    EXPECT_EQ(b->oldLayout, from) << pass << ", " << image;
    EXPECT_EQ(b->newLayout, to) << pass << ", " << image;
    return b;
}

bool runs(const Frame& frame, const std::string& pass) {
    std::vector<std::string> names = running(frame);
    return std::find(names.begin(), names.end(), pass) != names.end();
}

const std::vector<std::string> kSsao{"ssao_obscurance", "ssao_temporal_blur"};
const std::vector<std::string> kDepthOfField{"dof_downsample", "dof_gather", "dof_flood_fill", "dof_composite"};
const std::vector<std::string> kMotionBlur{"motion_blur_tile_max", "motion_blur_neighbour_max",
                                           "motion_blur_gather_fine", "motion_blur_gather_coarse"};

std::vector<std::string> concat(std::initializer_list<std::vector<std::string>> parts) {
    std::vector<std::string> all;
    for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
}

// The defaults: SSAO and temporal AA on, one sample, a pinhole camera, a closed shutter.
void TheDefaultFrameRunsEveryStepOnce() {
    Wiring w;
    const Frame& frame = w.render();
    EXPECT_EQ(running(frame), concat({{"shadow_maps", "gbuffer"},
                                      kSsao,
                                      {"lighting", "transparent", "temporal_aa", "aov_readback"}}));
    EXPECT_TRUE(passesThat(frame, true).empty());
}

// A frame without transparent surfaces runs no pass for them: the readback reads one texel of
// coverage 0.
void WithoutTransparentSurfacesNoPassRunsForThem() {
    Wiring w;
    w.source.withGlass = false;
    const Frame& frame = w.render();
    EXPECT_EQ(running(frame), concat({{"shadow_maps", "gbuffer"}, kSsao, {"lighting", "temporal_aa", "aov_readback"}}));
    EXPECT_TRUE(passesThat(frame, true).empty());
    EXPECT_EQ(barrier(frame, "aov_readback", "transparentCoverage.none"), nullptr);
}

// What the frame graph derives from the declarations, for the G-buffer's depth: written as an
// attachment, then sampled by compute passes in the read-only depth layout, after the writes.
void TheGBufferIsReadAfterItsWritesInReadOnlyLayouts() {
    Wiring w;
    const Frame& frame = w.render();
    const gpu::PlannedBarrier* write = transition(frame, "gbuffer", "gbuffer.depth", VK_IMAGE_LAYOUT_UNDEFINED,
                                                  VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    ASSERT_NE(write, nullptr);
    const gpu::PlannedBarrier* read =
        transition(frame, "ssao_obscurance", "gbuffer.depth", VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    ASSERT_NE(read, nullptr);
    EXPECT_TRUE(read->srcAccess & VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    EXPECT_TRUE(read->dstStage & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    // Read again in the same layout, with nothing written in between: no second barrier.
    EXPECT_EQ(barrier(frame, "lighting", "gbuffer.depth"), nullptr);
    // The transparent pass blends over the light accumulation: colour writes after compute writes.
    const gpu::PlannedBarrier* blend = transition(frame, "transparent", "lightAccumulation", VK_IMAGE_LAYOUT_GENERAL,
                                                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    ASSERT_NE(blend, nullptr);
    EXPECT_TRUE(blend->srcAccess & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    // Textures are read where their upload left them: no barrier.
    EXPECT_EQ(barrier(frame, "gbuffer", "bestFitNormals"), nullptr);
    EXPECT_EQ(barrier(frame, "aov_readback", "displayLut"), nullptr);
}

// Temporal AA's second frame reads the history the first wrote and writes the image the first
// read, each from the layout the first frame left it in: no layout is carried by hand.
void TemporalAaReadsLastFramesHistory() {
    Wiring w;
    const Frame& first = w.render();
    const gpu::PlannedBarrier* empty = barrier(first, "temporal_aa", "temporalAaHistory.previous");
    ASSERT_NE(empty, nullptr);
    EXPECT_EQ(empty->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    const Frame& second = w.render();
    // An unchanged scene: the still's running mean.
    EXPECT_TRUE(runs(second, "temporal_aa_still"));
    // 1TX's result is the history it writes: tone mapping sampled it last, and the last frame's
    // writes are waited for (the graph knows no more of another submission than that it wrote).
    const gpu::PlannedBarrier* previous =
        transition(second, "temporal_aa_still", "temporalAaHistory.previous", VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    ASSERT_NE(previous, nullptr);
    EXPECT_TRUE(previous->srcAccess & VK_ACCESS_2_MEMORY_WRITE_BIT);
    const gpu::PlannedBarrier* current = transition(second, "temporal_aa_still", "temporalAaHistory",
                                                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    ASSERT_NE(current, nullptr);
    // SSAO's history depth is read by nothing but the next frame: it stays as its pass wrote it.
    const gpu::PlannedBarrier* ssao = barrier(second, "ssao_temporal_blur", "ssaoHistoryDepth.previous");
    ASSERT_NE(ssao, nullptr);
    EXPECT_EQ(ssao->oldLayout, VK_IMAGE_LAYOUT_GENERAL);
    // The shadow atlas is kept: an unchanged scene renders no shadow map.
    EXPECT_FALSE(runs(second, "shadow_maps"));
    const gpu::PlannedBarrier* atlas = barrier(second, "lighting", "shadowAtlas");
    ASSERT_NE(atlas, nullptr);
    EXPECT_EQ(atlas->oldLayout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
}

void MsaaResolvesBeforeThePerPixelPassesAndLightsPerSample() {
    Wiring w;
    w.settings.msaaSamples = 4;
    const Frame& frame = w.render();
    EXPECT_EQ(running(frame), concat({{"shadow_maps", "gbuffer", "msaa_resolve"},
                                      kSsao,
                                      {"lighting", "transparent", "temporal_aa", "aov_readback"}}));
    // The resolve reads every multisampled target in a compute shader, after their writes: no
    // raster pass copies what compute cannot write when no clip volume needs a depth/stencil target.
    for (const char* target : {"gbuffer.normalRoughness", "gbuffer.albedoMetallic", "gbuffer.instance"}) {
        const gpu::PlannedBarrier* b =
            transition(frame, "msaa_resolve", target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        ASSERT_NE(b, nullptr);
        EXPECT_TRUE(b->dstStage & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT) << target;
    }
    // SSAO works on the resolved G-buffer's depth as the resolve stored it; the lighting reads the
    // tagged quads from the resolve's stencil image.
    transition(frame, "ssao_obscurance", "resolved.centreDepth", VK_IMAGE_LAYOUT_GENERAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(barrier(frame, "ssao_obscurance", "gbuffer.depth"), nullptr);
    EXPECT_NE(barrier(frame, "lighting", "resolved.edgeStencil"), nullptr);
}

void MsaaWithClipVolumesCopiesTheDepthAndMaskIntoADepthStencilTarget() {
    Wiring w;
    w.source.withClipVolume = true;
    w.settings.msaaSamples = 4;
    const Frame& frame = w.render();
    EXPECT_EQ(running(frame), concat({{"shadow_maps", "gbuffer", "msaa_resolve", "msaa_resolve_depth", "clip_volumes"},
                                      kSsao,
                                      {"lighting", "transparent", "temporal_aa", "aov_readback"}}));
    for (const char* image : {"resolved.centreDepth", "resolved.edgeStencil"}) {
        const gpu::PlannedBarrier* b = transition(frame, "msaa_resolve_depth", image, VK_IMAGE_LAYOUT_GENERAL,
                                                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        ASSERT_NE(b, nullptr);
        EXPECT_TRUE(b->dstStage & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT) << image;
    }
    // The raster half overwrites its target whole: nothing is loaded.
    for (const auto& pass : frame.passes)
        if (pass.name == "msaa_resolve_depth")
            for (const auto& attachment : pass.attachments)
                EXPECT_NE(attachment.load, VK_ATTACHMENT_LOAD_OP_LOAD);
    // The clip volumes mark the depth/stencil target, which SSAO then reads.
    const gpu::PlannedBarrier* resolved = barrier(frame, "ssao_obscurance", "resolved.depth");
    ASSERT_NE(resolved, nullptr);
    EXPECT_EQ(resolved->oldLayout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(barrier(frame, "lighting", "resolved.edgeStencil"), nullptr);
}

void WithoutSsaoTheLightingReadsOneUnoccludedTexel() {
    Wiring w;
    w.settings.ssao = false;
    const Frame& frame = w.render();
    for (const std::string& pass : kSsao) EXPECT_FALSE(runs(frame, pass)) << pass;
    EXPECT_EQ(barrier(frame, "lighting", "ssao.off"), nullptr);
    EXPECT_TRUE(runs(frame, "lighting"));
}

void WithoutTemporalAaTheReadbackReadsTheLightAccumulation() {
    Wiring w;
    w.settings.temporalAa = false;
    const Frame& frame = w.render();
    EXPECT_FALSE(runs(frame, "temporal_aa"));
    const gpu::PlannedBarrier* read = barrier(frame, "aov_readback", "lightAccumulation");
    ASSERT_NE(read, nullptr);
    EXPECT_EQ(read->oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);  // the transparents blended into it
    EXPECT_EQ(read->newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// Seed 000 "MB or DOF first?": depth of field, then motion blur, both after temporal AA in a
// real-time frame; a still's samples blur their own stratum of the aperture before the mean.
void DepthOfFieldAndMotionBlurFollowTemporalAa() {
    Wiring w;
    w.openLens();
    w.openShutter();
    const Frame& realTime = w.render();
    EXPECT_EQ(running(realTime), concat({{"shadow_maps", "gbuffer"},
                                         kSsao,
                                         {"lighting", "transparent", "temporal_aa"},
                                         kDepthOfField,
                                         kMotionBlur,
                                         {"aov_readback"}}));
    // The moving draw writes velocities into a target of their own.
    EXPECT_NE(barrier(realTime, "gbuffer", "gbuffer.velocity"), nullptr);
    const Frame& sample = w.render();
    EXPECT_EQ(running(sample), concat({{"gbuffer"},
                                       kSsao,
                                       {"lighting", "transparent", "temporal_aa_sample"},
                                       kDepthOfField,
                                       kMotionBlur,
                                       {"temporal_aa_still", "aov_readback"}}));
}

// The passes of the depth-of-field chain live a pass or two each: their images share memory.
void ShortLivedImagesShareMemory() {
    Wiring w;
    w.openLens();
    const Frame& frame = w.render();
    EXPECT_LT(frame.memory.bytes(), frame.memory.unaliasedBytes());
}

// Reference mode: each sub-frame lights its own viewpoint and adds it to the sum (the first
// writes it afresh, the next add to what the last left, in GENERAL); the frame itself resolves the
// mean and tone-maps it, with no lighting, temporal AA or shadow map of its own.
void ReferenceSubFramesAccumulateAndTheFrameResolvesTheMean() {
    Wiring w;
    w.settings.referenceSubFrames = 4;
    w.render();
    ASSERT_EQ(w.backend.frames.size(), 5u);
    for (size_t k = 0; k < 4; ++k) {
        const Frame& sub = w.backend.frames[k];
        EXPECT_EQ(running(sub), concat({{"shadow_maps", "gbuffer"}, kSsao, {"lighting", "transparent", "accumulate"}}))
            << "sub-frame " << k;
        const gpu::PlannedBarrier* sum = barrier(sub, "accumulate", "referenceAccumulation");
        ASSERT_NE(sum, nullptr);
        EXPECT_EQ(sum->oldLayout, k == 0 ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_GENERAL) << "sub-frame " << k;
    }
    const Frame& resolve = w.backend.frames[4];
    EXPECT_EQ(running(resolve),
              (std::vector<std::string>{"gbuffer", "accumulate_resolve", "aov_readback"}));
}

// Culling: with no AOV bound and no temporal AA history to write, nothing reads the light
// accumulation, and the lighting and what feeds it alone are culled; what writes a history still
// runs, since the next frame reads it.
void APassWhoseResultsNobodyReadsIsCulled() {
    Wiring w;
    w.request.aovs.clear();
    w.settings.temporalAa = false;
    const Frame& frame = w.render();
    EXPECT_EQ(passesThat(frame, true), (std::vector<std::string>{"lighting", "transparent"}));
    EXPECT_TRUE(runs(frame, "ssao_temporal_blur"));
    EXPECT_TRUE(runs(frame, "shadow_maps"));
    EXPECT_TRUE(runs(frame, "gbuffer"));
}

// Hybrid AA (seed 004): while the scene changes, near instances are edge-anti-aliased after
// temporal AA; a still accumulates them with the rest.
void HybridAaAddsEdgeAaWhileTheSceneChanges() {
    Wiring w;
    w.settings.hybridAaDistanceMetres = 1.0;
    const Frame& changing = w.render();
    EXPECT_EQ(running(changing), concat({{"shadow_maps", "gbuffer"},
                                         kSsao,
                                         {"lighting", "transparent", "temporal_aa", "edge_aa_edges",
                                          "edge_aa_weights", "edge_aa_blend", "aov_readback"}}));
    const Frame& still = w.render();
    EXPECT_FALSE(runs(still, "edge_aa_edges"));
}


// Each group runs in one process: the renderer's construction (its best-fit normal table) costs
// seconds, the frames milliseconds.
// Occlusion culling: the coverage buffer is reduced from the G-buffer's depth, right after it; not
// in reference mode, nor where a draw moves within the shutter (its depth would not stand).
void OcclusionCullingReducesTheDepthAfterTheGBuffer() {
    Wiring w;
    w.settings.occlusionCulling = true;
    w.settings.occlusionCullingRoute = OcclusionCullingRoute::CoverageBuffer;
    std::vector<std::string> names = running(w.render());
    auto gbuffer = std::find(names.begin(), names.end(), "gbuffer");
    ASSERT_NE(gbuffer, names.end());
    ASSERT_NE(gbuffer + 1, names.end());
    EXPECT_EQ(*(gbuffer + 1), "coverage_buffer");
    w.openShutter();
    EXPECT_FALSE(runs(w.render(), "coverage_buffer")) << "the opaque draw moves within the shutter";
    Wiring reference;
    reference.settings.occlusionCulling = true;
    reference.settings.referenceSubFrames = 2;
    EXPECT_FALSE(runs(reference.render(), "coverage_buffer"));
}

// Occlusion culling on the GPU: the G-buffer in two passes, the early culling before the first,
// the depth pyramid of its depth and the late culling between them; the culled draws' commands
// are indirect reads of the G-buffer passes. Not in reference mode; a draw moving within the
// shutter is drawn as it is, so a frame without a still draw culls nothing.
void GpuOcclusionCullingSplitsTheGBufferAroundTheDepthPyramid() {
    Wiring w;
    w.settings.occlusionCulling = true;
    std::vector<std::string> names = running(w.render());
    auto early = std::find(names.begin(), names.end(), "occlusion_cull_early");
    ASSERT_NE(early, names.end());
    // The first frame clears the new stamps, and every frame starts its commands from the host's
    // and hands their counts back; the test's image has levels above 5 (hi_z_top).
    ASSERT_GE(early - names.begin(), 2);
    ASSERT_GE(names.end() - early, 7);
    EXPECT_EQ(std::vector<std::string>(early - 2, early + 7),
              (std::vector<std::string>{"occlusion_stamps_clear", "occlusion_commands", "occlusion_cull_early",
                                        "gbuffer", "hi_z", "hi_z_top", "occlusion_cull_late", "gbuffer_late",
                                        "occlusion_counts"}));
    EXPECT_FALSE(runs(w.backend.frames.back(), "coverage_buffer"));
    const Frame& frame = w.backend.frames.back();
    for (const char* pass : {"gbuffer", "gbuffer_late"}) {
        bool waits = false;
        for (const auto& p : frame.passes)
            if (p.name == pass)
                for (const auto& b : p.barriers)
                    waits |= !b.isImage && b.dstAccess == VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT &&
                             b.srcStage == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
        EXPECT_TRUE(waits) << pass << " waits for the culling pass's commands";
    }
    EXPECT_FALSE(runs(w.render(), "occlusion_stamps_clear")) << "the stamps are kept from frame to frame";
    w.openShutter();
    EXPECT_FALSE(runs(w.render(), "occlusion_cull_early")) << "the opaque draw moves within the shutter";
    Wiring reference;
    reference.settings.occlusionCulling = true;
    reference.settings.referenceSubFrames = 2;
    EXPECT_FALSE(runs(reference.render(), "occlusion_cull_early"));
}

TEST(FrameWiring, TheDefaultFrame) {
    {
        SCOPED_TRACE("TheDefaultFrameRunsEveryStepOnce");
        TheDefaultFrameRunsEveryStepOnce();
    }
    {
        SCOPED_TRACE("WithoutTransparentSurfacesNoPassRunsForThem");
        WithoutTransparentSurfacesNoPassRunsForThem();
    }
    {
        SCOPED_TRACE("TheGBufferIsReadAfterItsWritesInReadOnlyLayouts");
        TheGBufferIsReadAfterItsWritesInReadOnlyLayouts();
    }
    {
        SCOPED_TRACE("TemporalAaReadsLastFramesHistory");
        TemporalAaReadsLastFramesHistory();
    }
    {
        SCOPED_TRACE("APassWhoseResultsNobodyReadsIsCulled");
        APassWhoseResultsNobodyReadsIsCulled();
    }
}

TEST(FrameWiring, SettingsChooseThePasses) {
    {
        SCOPED_TRACE("MsaaResolvesBeforeThePerPixelPassesAndLightsPerSample");
        MsaaResolvesBeforeThePerPixelPassesAndLightsPerSample();
    }
    {
        SCOPED_TRACE("MsaaWithClipVolumesCopiesTheDepthAndMaskIntoADepthStencilTarget");
        MsaaWithClipVolumesCopiesTheDepthAndMaskIntoADepthStencilTarget();
    }
    {
        SCOPED_TRACE("WithoutSsaoTheLightingReadsOneUnoccludedTexel");
        WithoutSsaoTheLightingReadsOneUnoccludedTexel();
    }
    {
        SCOPED_TRACE("WithoutTemporalAaTheReadbackReadsTheLightAccumulation");
        WithoutTemporalAaTheReadbackReadsTheLightAccumulation();
    }
    {
        SCOPED_TRACE("HybridAaAddsEdgeAaWhileTheSceneChanges");
        HybridAaAddsEdgeAaWhileTheSceneChanges();
    }
    {
        SCOPED_TRACE("OcclusionCullingReducesTheDepthAfterTheGBuffer");
        OcclusionCullingReducesTheDepthAfterTheGBuffer();
    }
    {
        SCOPED_TRACE("GpuOcclusionCullingSplitsTheGBufferAroundTheDepthPyramid");
        GpuOcclusionCullingSplitsTheGBufferAroundTheDepthPyramid();
    }
}

TEST(FrameWiring, TheLensAndTheShutter) {
    {
        SCOPED_TRACE("DepthOfFieldAndMotionBlurFollowTemporalAa");
        DepthOfFieldAndMotionBlurFollowTemporalAa();
    }
    {
        SCOPED_TRACE("ShortLivedImagesShareMemory");
        ShortLivedImagesShareMemory();
    }
}

TEST(FrameWiring, ReferenceMode) {
    {
        SCOPED_TRACE("ReferenceSubFramesAccumulateAndTheFrameResolvesTheMean");
        ReferenceSubFramesAccumulateAndTheFrameResolvesTheMean();
    }
}

}  // namespace
}  // namespace obscura::renderer
