// The render delegate behind the C ABI: the prim store with dirty tracking, sync (pulling dirty
// prims from the host's scene delegate), and the frame (building the frame graph of passes).
#pragma once

#include "delegate/environment_cache.h"
#include "delegate/frame_scene_builder.h"
#include "delegate/geometry_cache.h"
#include "delegate/grading_chart.h"
#include "delegate/prims/camera.h"
#include "delegate/prims/curves.h"
#include "delegate/prims/implicit_surface.h"
#include "delegate/prims/instancer.h"
#include "delegate/prims/light.h"
#include "delegate/prims/material.h"
#include "delegate/prims/mesh.h"
#include "delegate/prims/render_buffer.h"
#include "delegate/render_settings.h"
#include "delegate/temporal_accumulation.h"
#include "delegate/texture_cache.h"
#include "gpu/frame_graph.h"
#include "gpu/timestamps.h"
#include "passes/color_grading_lut.h"
#include "passes/gbuffer.h"
#include "passes/lighting.h"
#include "passes/pipeline_cache.h"
#include "passes/shadow_maps.h"
#include "passes/ssao.h"
#include "passes/temporal_aa.h"

#include <obscura/obscura.h>

#include <chrono>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace obscura::delegate {

// A failure of an ABI call: its status and message.
struct ApiError {
    ObscuraStatus status;
    std::string message;
};

class RenderDelegate {
public:
    // Throws ApiError when no device can be had.
    explicit RenderDelegate(const ObscuraDelegateCreateInfo& info);
    ~RenderDelegate();

    void setSceneDelegate(const ObscuraSceneDelegate& sceneDelegate);
    void insertPrim(const std::string& type, const std::string& path);
    void removePrim(const std::string& path);
    void markDirty(const std::string& path, ObscuraDirtyBits bits);
    void setRenderSetting(const std::string& key, const ObscuraValue* value);
    // Returns OBSCURA_OK, or OBSCURA_ERROR_BAD_PRIM_DATA when prims were skipped.
    ObscuraStatus render(const ObscuraRenderPassDesc& desc);
    void map(const std::string& path, ObscuraMappedBuffer& out);
    void unmap(const std::string& path);
    const std::vector<gpu::PassTime>& passTimings() const { return timings_; }
    // Fills the counters of `out` and of the structs chained to its pNext that this delegate knows
    // (ObscuraMemoryStats), leaving every sType, pNext and structSize as the host set them.
    void stats(ObscuraRenderStats& out) const;
    // After a lost device every render is refused with OBSCURA_ERROR_DEVICE and `why`.
    void deviceLost(const std::string& why) { deviceLost_ = why; }
    int32_t primId(const std::string& path) const;

    std::string& lastError() { return lastError_; }
    void log(ObscuraLogLevel level, const std::string& message) const;

private:
    // `desc`: the render pass, whose viewport size implicit surfaces are tessellated for.
    void sync(double time, const Camera* camera, const ObscuraRenderPassDesc& desc);
    // Clip volumes, SSAO, the environment and deferred lighting of `scene` (built from `frame`)
    // into the light accumulation.
    // Deferred MSAA's part of the frame after the resolve (render setting msaa > 1): the
    // multisampled G-buffer behind the resolved one, for the per-sample lighting, and the max of
    // each pixel's sample depths, which the transparents test and fade against.
    struct MsaaFrame {
        passes::PerSampleLighting perSample;
        gpu::ImageHandle maxDepth;
    };
    gpu::ImageHandle addLighting(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                 const passes::GBuffer& gbuffer, gpu::ImageHandle shadowAtlas,
                                 const FrameSceneInputs& frame, gpu::ImageHandle& transparentCoverage,
                                 const MsaaFrame* msaa = nullptr);
    // Sample counts the G-buffer can be rendered and read with on this device (render setting msaa).
    VkSampleCountFlags offeredMsaaSampleCounts() const;
    // The light accumulation's format (render setting lighting:halfFloat).
    passes::LightAccumulation lightAccumulation() const;
    // Compiles, records and submits one frame graph, and waits for it.
    void executeFrame(gpu::FrameGraph& graph);
    // Reference mode: `count` sub-frames of `frame` sampling `lens`'s aperture, the `shutter`
    // interval (absolute time codes; empty: the frame's time) and the pixel through `pixelFilter`,
    // summed into accumulation_.
    void accumulateReference(const FrameSceneInputs& frame, const passes::ThinLens& lens, uint32_t count,
                             const std::array<double, 2>& shutter, const PixelFilter& pixelFilter);
    template <typename T>
    T* find(const std::string& path) const;

    PFN_obscuraLog logFn_ = nullptr;
    void* logUser_ = nullptr;
    bool failOnValidation_ = false;
    std::unique_ptr<gpu::Device> device_;
    std::unique_ptr<passes::PipelineCache> pipelines_;
    std::unique_ptr<gpu::TransientImagePool> transients_;
    std::unique_ptr<gpu::Timestamps> timestamps_;
    gpu::ImagePtr bestFitNormals_;
    struct {
        gpu::ImagePtr accessibility, halfDepth;
    } unoccluded_;
    // A frame without a velocity target reads this one texel of kStaticVelocity (the motion AOV).
    gpu::ImagePtr stillVelocity_;
    InstanceModels lastModels_;  // the last frame's instance models, for temporal AA's object motion
    struct {
        gpu::ImagePtr image;
        VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    } accumulation_;  // reference mode's running sum (passes/accumulate.h)
    // SSAO's temporal accumulation: the history and what it was rendered with, to reproject it or
    // reset it (size, projection, settings).
    passes::SsaoHistory ssaoHistory_;
    struct {
        bool valid = false;
        Matrix4d view = kIdentity, projection = kIdentity;
        uint32_t width = 0, height = 0;
        uint64_t settingsVersion = 0;
    } ssaoHistoryFrame_;
    // SSAO of the frame being built, whose history layouts executeFrame keeps once compiled, and
    // whether it imported the environment maps (whose layouts it keeps too).
    bool ssaoInFrame_ = false;
    bool environmentInFrame_ = false;
    // Temporal AA: its history images, the bookkeeping that decides how each frame uses them, and
    // whether the frame being built runs it (executeFrame keeps its history layouts).
    passes::TemporalAaHistory temporalAaHistory_;
    passes::ShadowAtlasHistory shadowHistory_;
    TemporalAccumulation temporalAccumulation_;
    bool temporalAaInFrame_ = false;
    bool converged_ = true;  // the last render's, for ObscuraRenderStats
    // Deferred MSAA: the lighting pass counts the pixels it lit per sample into this host-visible
    // uint (logged after each frame).
    gpu::BufferPtr msaaTaggedPixels_;
    std::unique_ptr<TextureCache> textures_;
    std::unique_ptr<GeometryCache> geometry_;
    std::unique_ptr<EnvironmentCache> environment_;
    // Textured domes beyond the first, last frame: warned about when the list changes.
    std::vector<std::string> ignoredDomes_;
    passes::ColorGradingLut grading_;
    GradingChartFile gradingChart_;

    ObscuraSceneDelegate sceneDelegate_{};
    bool hasSceneDelegate_ = false;
    std::map<std::string, std::unique_ptr<Prim>> prims_;
    // Prims with dirty bits: sync visits these only, so its cost follows what changed.
    std::set<Prim*> dirty_;
    // Counts insertions, removals and dirty marks: temporal AA restarts its mean when it moves.
    uint64_t sceneVersion_ = 0;
    int32_t nextPrimId_ = 0;
    RenderSettings settings_;

    std::vector<gpu::PassTime> timings_;
    uint32_t primsSynced_ = 0;
    uint64_t trianglesDrawn_ = 0;
    uint32_t lightsWithoutShadowRoom_ = 0;  // last frame's, so the warning is logged once per change
    std::vector<std::string> unclippedLights_;  // likewise
    double syncMilliseconds_ = 0.0;
    double frameSetupMilliseconds_ = 0.0;
    std::chrono::steady_clock::time_point frameRecorded_;
    std::string lastError_;
    std::string deviceLost_;  // empty while the device works
};

}  // namespace obscura::delegate
