// The render delegate behind the C ABI, as Hydra's: the prim store with dirty tracking, sync
// (pulling dirty prims from the host's scene delegate), render buffers, and the frame's scene built
// from the prims for the renderer (renderer/frame_renderer.h), which renders it.
#pragma once

#include "delegate/api_error.h"
#include "delegate/frame_scene_source.h"
#include "delegate/geometry_cache.h"
#include "delegate/prims/camera.h"
#include "delegate/prims/curves.h"
#include "delegate/prims/implicit_surface.h"
#include "delegate/prims/instancer.h"
#include "delegate/prims/light.h"
#include "delegate/prims/material.h"
#include "delegate/prims/mesh.h"
#include "delegate/prims/nurbs_patch.h"
#include "delegate/prims/render_buffer.h"
#include "delegate/texture_cache.h"
#include "gpu/external_memory.h"
#include "renderer/frame_renderer.h"
#include "renderer/render_settings.h"

#include <obscura/obscura.h>

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace obscura::delegate {

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
    // The ABI's display interop: the render buffer's memory (and the frames' semaphore) as file
    // descriptors the host imports.
    void exportBuffer(const std::string& path, ObscuraExternalBuffer& out);
    const std::vector<gpu::PassTime>& passTimings() const { return frame_->timings(); }
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
    // Syncs `prims` in order, their pulls on several threads when `parallel`; each prim's device work
    // and messages on this thread.
    void syncPrims(std::span<Prim* const> prims, const SyncContext& ctx, bool parallel);
    // Counts a synced prim and logs its problem and warnings.
    void reportSync(const Prim& prim);
    // Sample counts the G-buffer can be rendered and read with on this device (render setting msaa).
    VkSampleCountFlags offeredMsaaSampleCounts() const;
    template <typename T>
    T* find(const std::string& path) const;

    PFN_obscuraLog logFn_ = nullptr;
    void* logUser_ = nullptr;
    LogSink logSink_;  // log() for the layers below
    bool failOnValidation_ = false;
    std::unique_ptr<gpu::Device> device_;
    std::unique_ptr<TextureCache> textures_;
    std::unique_ptr<GeometryCache> geometry_;
    BuiltMeshCache builtMeshes_;
    std::unique_ptr<renderer::FrameRenderer> frame_;
    // Made by the first export: the semaphore of exported buffers and their release after each frame.
    std::unique_ptr<gpu::ExportTimeline> exportTimeline_;
    // Textured domes beyond the first, last frame: warned about when the list changes.
    std::vector<std::string> ignoredDomes_;

    ObscuraSceneDelegate sceneDelegate_{};
    bool hasSceneDelegate_ = false;
    std::map<std::string, std::unique_ptr<Prim>> prims_;
    // Prims with dirty bits: sync visits these only, so its cost follows what changed.
    std::set<Prim*> dirty_;
    // Counts insertions, removals and dirty marks: temporal AA restarts its mean when it moves.
    uint64_t sceneVersion_ = 0;
    uint64_t drawnVersion_ = 0;  // FrameRequest::drawnVersion
    int32_t nextPrimId_ = 0;
    renderer::RenderSettings settings_;

    uint32_t primsSynced_ = 0;
    FrameSceneReport sceneReport_;
    double syncMilliseconds_ = 0.0;
    double frameSetupMilliseconds_ = 0.0;
    std::string lastError_;
    std::string deviceLost_;  // empty while the device works
};

}  // namespace obscura::delegate
