// The frame (DESIGN.md "The frame"), apart from Hydra: the frame graph of passes wired for the
// settings, and every resource that lives from frame to frame (the SSAO, temporal AA and shadow
// histories, the reference's accumulation, the environment maps, the display LUT); the frame
// backend it runs on keeps the pipelines, the transient images and the timestamps. The delegate
// owns the prims and hands the renderer a source of the frame's scene, which the renderer asks for
// each viewpoint the frame needs: the frame's own, and each reference sub-frame's.
#pragma once

#include "gpu/frame_backend.h"
#include "gpu/history_images.h"
#include "gpu/log.h"
#include "passes/aov_readback.h"
#include "pass_support/color_grading_lut.h"
#include "passes/frame_scene.h"
#include "passes/gbuffer.h"
#include "passes/lighting.h"
#include "passes/shadow_maps.h"
#include "passes/ssao.h"
#include "passes/temporal_aa.h"
#include "pass_support/thin_lens.h"
#include "renderer/environment_cache.h"
#include "renderer/gpu_occlusion_culling.h"
#include "renderer/grading_chart.h"
#include "renderer/matrix.h"
#include "renderer/occlusion_history.h"
#include "renderer/render_settings.h"
#include "renderer/temporal_accumulation.h"

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace obscura::renderer {

// Where on the lens, when in the shutter and where within the pixel a reference sub-frame looks
// from (Camera::viewMatrix / projectionMatrix with a lens offset), and which point of each light's
// emitter lights it.
struct FrameSample {
    double time;                        // absolute time code, within the camera's shutter
    std::array<double, 2> lensOffset;   // camera space, scene units
    std::array<double, 2> pixelJitter;  // pixels
    std::array<double, 2> emitter;      // [0, 1)^2: where on each light's emitter (emitterSample)
};

// Temporal AA's object motion: every drawn instance's model by a key stable from frame to frame
// (instanceKey()), as the last frame drew it and as this one does.
using InstanceModels = std::unordered_map<uint64_t, Matrix4d>;

// What differs between the scenes one render asks for: where the camera looks from and when.
struct FrameViewpoint {
    std::optional<FrameSample> sample = std::nullopt;  // none: the pinhole camera at the frame's time
    // Temporal AA's sub-pixel shift, applied after the projection FrameSceneSource::view() gives
    // for everything that rasterises or reads the G-buffer (CameraData); the view and the shadow
    // cascades keep the unjittered frustum, so SSAO's history check and the cascades' texel grids
    // do not move with the jitter. Identity for reference sub-frames that jitter through `sample`.
    Matrix4d clipJitter = kIdentity;
    // A border this many pixels wide that the frame renders around the image: the scene is that
    // much larger, its projection widened so that the image's pixels stay where they were. A
    // reference sub-frame's samples resolved over the pixel's box take some of an edge pixel's
    // samples from beyond the edge.
    uint32_t guardPixels = 0;
    // Temporal AA's place in its jitter cycle (CameraData::noiseFrame): the shadow filter's turn.
    uint32_t noiseFrame = 0;
    // Hybrid AA (seed 004, render setting taa:hybridDistance in scene units): instances whose world
    // bounds come nearer the eye than this are drawn without the jitter and edge-anti-aliased
    // (kInstanceEdgeAa); the rest are temporally anti-aliased. 0: every instance is temporal.
    double edgeAaDistance = 0.0;
    // The camera's shutter, absolute time codes [open, close], when the frame samples it: a
    // motion-blurred frame (no `sample`) is seen at its centre (the reconstruction filter spreads
    // each pixel both ways along its velocity, McGuire et al. 2012) and the passes get where the
    // camera and every instance are at its ends; a reference sub-frame (`sample`) is seen at its
    // own time within it. None: the shutter is closed or not sampled (motionBlur off), the frame is
    // seen at the sync time.
    std::optional<std::array<double, 2>> shutter = std::nullopt;
    // The part of `shutter` a motion-blurred frame (no `sample`) covers, as fractions of it
    // [start, end]: the whole of it in a real-time frame; one stratum in a sample of a still's
    // accumulation (TemporalAaStep::shutterStratum). The frame is seen at the part's middle and its
    // velocities span the part alone.
    std::array<double, 2> shutterSpan{0.0, 1.0};
    // Where on the aperture a still's accumulated frame (no `sample`) looks from
    // (TemporalAaStep::lensStratum): camera space x right, y up, scene units, the focus plane kept
    // in place (Camera::projectionMatrix with a lens offset). Zero: the lens's centre.
    std::array<double, 2> lensOffset{0.0, 0.0};
    // How MSAA samples resolve (CameraData::sampleResolve): linearly in a sample of a still's mean.
    passes::SampleResolve sampleResolve = passes::SampleResolve::ToneMapped;
    // The samples of the mean this frame is one of (a still's accumulated frames, the reference's
    // sub-frames); 1 in a real-time frame. Each material texture lookup filters its own share of
    // the pixel (CameraData::textureLodBias).
    uint32_t meanSamples = 1;
    // Temporal AA: the last frame's models (instances whose model differs get an
    // InstanceReprojection record), and where this frame's go; null without temporal AA.
    const InstanceModels* lastModels = nullptr;
    InstanceModels* models = nullptr;
    // Occlusion culling (render setting occlusionCulling): the last frame's coverage buffer in this
    // viewpoint's view; draws and instances whose bounds it hides are left out of the camera's
    // draws. Null: nothing is culled (a reference sub-frame, a frame without history).
    const CoverageBuffer* occlusion = nullptr;
    // Occlusion culling on the GPU (occlusionCulling:route gpu): the draws that stay still leave
    // their instances inside the view to the culling pass (FrameScene::occlusionCandidates).
    bool gpuOcclusionCulling = false;
};

// World-to-view and view-to-clip (row-vector convention) a viewpoint sees through.
struct FrameView {
    Matrix4d view;
    Matrix4d projection;
};

// The scene of the frame, built by the delegate from its prims for any viewpoint.
class FrameSceneSource {
public:
    // The unjittered view of `viewpoint`.
    virtual FrameView view(const FrameViewpoint& viewpoint) const = 0;
    // The GPU records and draws of the scene seen from `viewpoint`.
    virtual passes::FrameScene scene(const FrameViewpoint& viewpoint) = 0;
    // Once the frame of scene() ran: what occlusion culling on the GPU left out of its camera
    // draws (whole draws, instances, triangles), which scene()'s counts could not yet hold.
    virtual void culledOnGpu(uint32_t draws, uint64_t instances, uint64_t triangles) = 0;

protected:
    ~FrameSceneSource() = default;
};

// The camera as the frame samples it.
struct FrameCamera {
    // Names the camera: another one is a cut, after which temporal AA starts afresh.
    std::string key;
    uint32_t width = 0, height = 0;
    // The physical lens (conformed to the image); the render setting dof decides whether the frame
    // samples it.
    passes::ThinLens lens;
    passes::ApertureShape aperture;
    std::array<double, 2> clippingRange{};
    double time = 0.0;  // the frame's time code
    // Absolute time codes [open, close] (open = close: closed); the render setting motionBlur
    // decides whether the frame samples it, else the frame is seen at `time`.
    std::array<double, 2> shutter{};
};

// One render: the camera, what it is rendered from and into.
struct FrameRequest {
    FrameCamera camera;
    // Counts the host's insertions, removals and dirty marks: while it moves the scene changes,
    // and temporal AA blends rather than averages.
    uint64_t sceneVersion = 0;
    // Counts the changes to what the G-buffer draws (meshes, instancers, materials; not cameras,
    // lights or render buffers): while it holds, the last frame's depth is still the scene's.
    uint64_t drawnVersion = 0;
    uint64_t settingsVersion = 0;  // RenderSettings::version()
    // The textured dome's latlong image the environment maps are made from, or null.
    gpu::ImagePtr environment;
    std::vector<passes::AovRequest> aovs;
};

class FrameRenderer {
public:
    // `environmentSampler`: trilinear, repeating in longitude and clamped in latitude.
    FrameRenderer(gpu::Device& device, VkSampler environmentSampler, LogSink log);
    // Frames on another backend (tests run them against a mock, without a GPU).
    FrameRenderer(gpu::FrameBackend& backend, VkSampler environmentSampler, LogSink log);
    ~FrameRenderer();
    FrameRenderer(const FrameRenderer&) = delete;
    FrameRenderer& operator=(const FrameRenderer&) = delete;

    // The display transform of `settings` (OCIO config, display, view, looks, the grading chart),
    // baked when it changed; returns the reason it cannot be had (the previous one stays).
    std::string updateDisplay(const FrameSettings& settings);
    // Renders one frame of `source` into the request's AOVs, and waits for it.
    void render(FrameSceneSource& source, const FrameRequest& request, const FrameSettings& settings);

    const std::vector<gpu::PassTime>& timings() const { return timings_; }
    // The last render left a still that another render would not change (ObscuraRenderStats).
    bool converged() const { return converged_; }
    // When the last frame's commands were recorded.
    std::chrono::steady_clock::time_point recorded() const { return backend_.recorded(); }

private:
    FrameRenderer(std::unique_ptr<gpu::FrameBackend> owned, gpu::FrameBackend* backend, VkSampler environmentSampler,
                  LogSink log);

    // Deferred MSAA's part of the frame after the resolve (render setting msaa > 1): the
    // multisampled G-buffer behind the resolved one, for the per-sample lighting, and the max of
    // each pixel's sample depths, which the transparents test and fade against.
    struct MsaaFrame {
        passes::PerSampleLighting perSample;
        gpu::ImageHandle maxDepth;
    };
    // The custom resolve of the multisampled `gbuffer` (replaced by the resolved one), with the
    // per-sample mask the lighting reads and the count of the pixels it tags.
    MsaaFrame addMsaaResolve(gpu::FrameGraph& graph, const passes::FrameScene& scene, passes::GBuffer& gbuffer);
    // Clip volumes (into `gbuffer`'s stencil), SSAO, the environment, deferred lighting and the
    // transparent surfaces of `scene`, seen through `seen`, into the light accumulation of format
    // `accumulation`.
    gpu::ImageHandle addLighting(gpu::FrameGraph& graph, const passes::FrameScene& scene, passes::GBuffer& gbuffer,
                                 gpu::ImageHandle shadowAtlas, const FrameView& seen, const FrameRequest& request,
                                 const FrameSettings& settings, passes::LightAccumulation accumulation,
                                 gpu::ImageHandle& transparentCoverage, const MsaaFrame* msaa = nullptr);
    // Runs one frame graph and waits for it.
    void executeFrame(gpu::FrameGraph& graph);
    // Reference mode: `count` sub-frames sampling `lens`'s aperture, the `shutter` interval (absolute
    // time codes; empty: the frame's time) and the pixel through the pixel filter, summed into
    // accumulation_.
    void accumulateReference(FrameSceneSource& source, const FrameRequest& request, const FrameSettings& settings,
                             const passes::ThinLens& lens, const std::array<double, 2>& shutter);

    std::unique_ptr<gpu::FrameBackend> ownedBackend_;
    gpu::FrameBackend& backend_;
    LogSink log_;
    gpu::ImagePtr bestFitNormals_;
    struct {
        gpu::ImagePtr accessibility, halfDepth;
    } unoccluded_;
    // A frame without a velocity target reads this one texel of kStaticVelocity (the motion AOV).
    gpu::ImagePtr stillVelocity_;
    // A frame without transparent surfaces reads this one texel of coverage 0.
    gpu::ImagePtr noTransparentCoverage_;
    OcclusionHistory occlusion_;
    GpuOcclusionCulling gpuOcclusion_;
    InstanceModels lastModels_;  // the last frame's instance models, for temporal AA's object motion
    gpu::PersistentImage accumulation_;  // reference mode's running sum (passes/accumulate.h)
    // SSAO's temporal accumulation: the history and what it was rendered with, to reproject it or
    // reset it (size, projection, settings).
    passes::SsaoHistory ssaoHistory_;
    struct {
        bool valid = false;
        Matrix4d view = kIdentity, projection = kIdentity;
        uint32_t width = 0, height = 0;
        uint64_t settingsVersion = 0;
    } ssaoHistoryFrame_;
    // Temporal AA: its history images and the bookkeeping that decides how each frame uses them.
    passes::TemporalAaHistory temporalAaHistory_;
    passes::ShadowAtlasHistory shadowHistory_;
    TemporalAccumulation temporalAccumulation_;
    bool converged_ = true;
    // Deferred MSAA: the lighting pass counts the pixels it lit per sample into this host-visible
    // uint (logged after each frame).
    gpu::BufferPtr msaaTaggedPixels_;
    std::unique_ptr<EnvironmentCache> environment_;
    passes::ColorGradingLut grading_;
    GradingChartFile gradingChart_;
    std::vector<gpu::PassTime> timings_;
    VkDeviceSize transientBytes_ = 0;  // the last frame's transient images (logged when it changes)
};

}  // namespace obscura::renderer
