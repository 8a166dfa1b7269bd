#include "delegate/render_delegate.h"

#include "delegate/aov_bindings.h"
#include "delegate/cache_folder.h"
#include "delegate/chained_stats.h"
#include "delegate/purposes.h"
#include "gpu/vk_check.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace obscura::delegate {
namespace {

// Hydra's sync order: sprims (cameras, lights, materials) and bprims before the rprims that
// reference them.
int syncOrder(const Prim& p) {
    std::string category = p.schema().category;
    return category == "rprim" ? 1 : 0;
}

// Whether a change to the prim may change what the G-buffer draws (occlusion culling's history,
// FrameRequest::drawnVersion): anything but cameras, lights and render buffers.
bool changesWhatIsDrawn(const Prim& prim) {
    return !dynamic_cast<const Camera*>(&prim) && !dynamic_cast<const Light*>(&prim) &&
           !dynamic_cast<const RenderBuffer*>(&prim);
}

}  // namespace

RenderDelegate::RenderDelegate(const ObscuraDelegateCreateInfo& info) {
    logFn_ = info.log;
    logUser_ = info.logUserData;
    bool validation = info.validation == 1;
    if (info.validation < 0) {
        const char* env = std::getenv("OBSCURA_VALIDATION");
        validation = env && std::strcmp(env, "0") != 0 && *env;
    }
    failOnValidation_ = validation;
    gpu::ContextOptions options;
    options.deviceSelector = info.device ? info.device : "";
    options.validation = validation;
    std::string faultProblem;
    options.faults = gpu::FaultInjection::fromEnvironment(&faultProblem);
    logSink_ = [this](LogLevel level, const std::string& message) {
        log(level == LogLevel::Error     ? OBSCURA_LOG_ERROR
            : level == LogLevel::Warning ? OBSCURA_LOG_WARNING
            : level == LogLevel::Info    ? OBSCURA_LOG_INFO
                                         : OBSCURA_LOG_DEBUG,
            message);
    };
    options.log = logSink_;
    auto context = gpu::Context::create(options);
    if (!context) throw ApiError{OBSCURA_ERROR_DEVICE, context.error()};
    device_ = std::make_unique<gpu::Device>(std::move(*context), cacheFolderFromEnvironment("OBSCURA_PIPELINE_CACHE"));
    textures_ = std::make_unique<TextureCache>(*device_, options.log,
                                               TextureDiskCache(cacheFolderFromEnvironment("OBSCURA_TEXTURE_CACHE")));
    geometry_ = std::make_unique<GeometryCache>(*device_);
    frame_ = std::make_unique<renderer::FrameRenderer>(*device_, textures_->sampler(WrapMode::Repeat, WrapMode::Clamp),
                                                       options.log);
    log(OBSCURA_LOG_INFO, "device: " + device_->context().summary().name);
    if (!faultProblem.empty()) log(OBSCURA_LOG_WARNING, faultProblem);
}

RenderDelegate::~RenderDelegate() {
    vkDeviceWaitIdle(device_->vk());
    prims_.clear();
    exportTimeline_.reset();
    frame_.reset();
    textures_.reset();
    geometry_.reset();
    device_.reset();
}

void RenderDelegate::log(ObscuraLogLevel level, const std::string& message) const {
    if (logFn_) {
        logFn_(logUser_, level, message.c_str());
    } else if (level >= OBSCURA_LOG_WARNING) {
        std::fprintf(stderr, "obscura: %s: %s\n", level == OBSCURA_LOG_ERROR ? "error" : "warning", message.c_str());
    }
}

template <typename T>
T* RenderDelegate::find(const std::string& path) const {
    auto it = prims_.find(path);
    return it == prims_.end() ? nullptr : dynamic_cast<T*>(it->second.get());
}

void RenderDelegate::setSceneDelegate(const ObscuraSceneDelegate& sd) {
    if (sd.structSize < sizeof(ObscuraSceneDelegate) || sd.sType != OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE)
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "ObscuraSceneDelegate: wrong sType or structSize"};
    if (!sd.getValue) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "ObscuraSceneDelegate.getValue is required"};
    sceneDelegate_ = sd;
    hasSceneDelegate_ = true;
    ++sceneVersion_;
    ++drawnVersion_;
    for (auto& [path, prim] : prims_) {
        prim->markDirty(OBSCURA_DIRTY_ALL);
        dirty_.insert(prim.get());
    }
}

void RenderDelegate::insertPrim(const std::string& type, const std::string& path) {
    if (path.empty() || path[0] != '/')
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "prim path '" + path + "' is not absolute"};
    const schema::PrimSchema* schema = schema::findPrimSchema(type);
    if (!schema) throw ApiError{OBSCURA_ERROR_UNKNOWN_TYPE, "unknown prim type '" + type + "'"};
    if (prims_.count(path)) throw ApiError{OBSCURA_ERROR_ALREADY_EXISTS, "a prim already exists at " + path};
    std::unique_ptr<Prim> prim;
    if (type == "mesh") prim = std::make_unique<Mesh>(path, *schema, nextPrimId_++);
    else if (auto kind = ImplicitSurface::kindOf(type)) prim = std::make_unique<ImplicitSurface>(path, *schema, nextPrimId_++, *kind);
    else if (type == "basisCurves") prim = std::make_unique<Curves>(path, *schema, nextPrimId_++);
    else if (type == "nurbsPatch") prim = std::make_unique<NurbsPatch>(path, *schema, nextPrimId_++);
    else if (type == "points") prim = std::make_unique<Points>(path, *schema, nextPrimId_++);
    else if (type == "camera") prim = std::make_unique<Camera>(path, *schema);
    else if (type == "distantLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Distant);
    else if (type == "sphereLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Sphere);
    else if (type == "rectLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Rect);
    else if (type == "diskLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Disk);
    else if (type == "cylinderLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Cylinder);
    else if (type == "domeLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Dome);
    else if (type == "material") prim = std::make_unique<Material>(path, *schema);
    else if (type == "renderBuffer") prim = std::make_unique<RenderBuffer>(path, *schema);
    else if (type == "instancer") prim = std::make_unique<Instancer>(path, *schema);
    else throw ApiError{OBSCURA_ERROR_UNKNOWN_TYPE, "prim type '" + type + "' has a schema but no implementation"};
    dirty_.insert(prim.get());
    if (changesWhatIsDrawn(*prim)) ++drawnVersion_;
    prims_.emplace(path, std::move(prim));
    ++sceneVersion_;
}

void RenderDelegate::removePrim(const std::string& path) {
    // GPU resources the prim owns are retired: they die at the end of the next frame.
    auto it = prims_.find(path);
    if (it == prims_.end()) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no prim at " + path};
    dirty_.erase(it->second.get());
    if (changesWhatIsDrawn(*it->second)) ++drawnVersion_;
    prims_.erase(it);
    ++sceneVersion_;
}

void RenderDelegate::markDirty(const std::string& path, ObscuraDirtyBits bits) {
    auto it = prims_.find(path);
    if (it == prims_.end()) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no prim at " + path};
    it->second->markDirty(bits);
    if (bits != OBSCURA_DIRTY_CLEAN) {
        dirty_.insert(it->second.get());
        ++sceneVersion_;
        if (changesWhatIsDrawn(*it->second)) ++drawnVersion_;
    }
}

VkSampleCountFlags RenderDelegate::offeredMsaaSampleCounts() const {
    const VkPhysicalDeviceLimits& limits = device_->context().properties().limits;
    return limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts &
           limits.framebufferStencilSampleCounts & limits.sampledImageColorSampleCounts &
           limits.sampledImageIntegerSampleCounts & limits.sampledImageDepthSampleCounts;
}

void RenderDelegate::setRenderSetting(const std::string& key, const ObscuraValue* value) {
    const renderer::FrameSettings& values = settings_.values();
    const int32_t previousRefineLevel = values.refineLevel;
    const double previousTimeCodesPerSecond = values.timeCodesPerSecond;
    const bool previousCompression = values.textureCompression;
    int32_t previousMsaa = int32_t(values.msaaSamples);
    std::string problem = settings_.set(key, value);
    if (!problem.empty())
        throw ApiError{renderer::findRenderSetting(key) ? OBSCURA_ERROR_INVALID_ARGUMENT : OBSCURA_ERROR_NOT_FOUND, problem};
    // A sample count the device does not offer is refused (not clamped: a host asking for 8 samples
    // and silently getting 4 would compare the wrong images), and the previous count stays.
    if (int32_t samples = int32_t(values.msaaSamples); key == "msaa" && samples != previousMsaa) {
        std::string offered;
        for (int32_t n = 1; n <= 64; n *= 2)
            if (offeredMsaaSampleCounts() & VkSampleCountFlags(n)) offered += (offered.empty() ? "" : ", ") + std::to_string(n);
        bool powerOfTwo = (samples & (samples - 1)) == 0;
        if (!powerOfTwo || !(offeredMsaaSampleCounts() & VkSampleCountFlags(samples))) {
            ObscuraValue previous{OBSCURA_VALUE_INT, 0, 1, &previousMsaa};
            settings_.set(key, &previous);
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT,
                           "msaa: " + std::to_string(samples) + " samples per pixel " +
                               (powerOfTwo ? "are not offered by " + device_->context().summary().name
                                           : std::string("is not a sample count")) +
                               " (it offers " + offered + ")"};
        }
        // The resolve and the per-sample lighting place samples at Vulkan's standard locations.
        if (samples > 1 && !device_->context().properties().limits.standardSampleLocations)
            log(OBSCURA_LOG_WARNING, "msaa: the device does not use the standard sample locations; depths and "
                                     "per-sample positions will be slightly off");
    }
    // A new refinement level re-refines every mesh (Hydra's display-style change).
    if (values.refineLevel != previousRefineLevel)
        for (auto& [path, prim] : prims_)
            if (dynamic_cast<Mesh*>(prim.get())) markDirty(path, kDirtyTessellation);
    // Materials read their textures again, stored the new way.
    if (values.textureCompression != previousCompression) {
        textures_->setCompression(values.textureCompression);
        for (auto& [path, prim] : prims_)
            if (dynamic_cast<Material*>(prim.get())) markDirty(path, OBSCURA_DIRTY_PARAMS);
    }
    // Velocities are per second: another rate moves points and instances elsewhere in the shutter.
    if (values.timeCodesPerSecond != previousTimeCodesPerSecond)
        for (auto& [path, prim] : prims_)
            if (const schema::AttributeSchema* velocities = schema::findAttribute(prim->schema(), "velocities"))
                markDirty(path, velocities->dirtyBit);
}

void RenderDelegate::reportSync(const Prim& prim) {
    ++primsSynced_;
    if (prim.skipped()) log(OBSCURA_LOG_ERROR, "skipped prim " + prim.problem());
    if (auto* mesh = dynamic_cast<const Mesh*>(&prim))
        for (const auto& w : mesh->warnings()) log(OBSCURA_LOG_WARNING, w);
    if (auto* instancer = dynamic_cast<const Instancer*>(&prim))
        for (const auto& w : instancer->warnings()) log(OBSCURA_LOG_WARNING, w);
    if (auto* material = dynamic_cast<const Material*>(&prim))
        for (const auto& w : material->warnings()) log(OBSCURA_LOG_WARNING, material->path() + ": " + w);
    if (auto* light = dynamic_cast<const Light*>(&prim); light && !light->warning().empty())
        log(OBSCURA_LOG_WARNING, light->path() + ": " + light->warning());
    if (auto* cam = dynamic_cast<const Camera*>(&prim); cam && !cam->warning().empty())
        log(OBSCURA_LOG_WARNING, cam->path() + ": " + cam->warning());
}

void RenderDelegate::syncPrims(std::span<Prim* const> prims, const SyncContext& ctx, bool parallel) {
    if (!parallel || prims.size() < 2) {
        for (Prim* prim : prims) {
            prim->sync(ctx);
            reportSync(*prim);
        }
        return;
    }
    // Hydra's parallel rprim sync: the pulls (the host's callbacks, triangulation, refinement) on
    // TBB's threads, each prim's device work and messages after them on this thread, in order.
    std::vector<DeviceWork> work(prims.size());
    tbb::parallel_for(size_t(0), prims.size(), [&](size_t i) {
        SyncContext own = ctx;
        own.deviceWork = &work[i];
        prims[i]->pullDirty(own);
    });
    for (size_t i = 0; i < prims.size(); ++i) {
        prims[i]->commit(work[i]);
        reportSync(*prims[i]);
    }
}

void RenderDelegate::sync(double time, const Camera* camera, const ObscuraRenderPassDesc& desc) {
    primsSynced_ = 0;
    // The camera first (its shutter decides the interval transforms are sampled over), then
    // sprims and bprims, then rprims.
    std::vector<Prim*> dirty(dirty_.begin(), dirty_.end());
    dirty_.clear();
    std::sort(dirty.begin(), dirty.end(), [camera](Prim* a, Prim* b) {
        int oa = a == camera ? -1 : syncOrder(*a), ob = b == camera ? -1 : syncOrder(*b);
        return oa != ob ? oa < ob : a->path() < b->path();
    });
    const renderer::FrameSettings& settings = settings_.values();
    SyncContext ctx{sceneDelegate_, *device_,      time, time, time, settings.refineLevel, settings.timeCodesPerSecond,
                    *textures_,     *geometry_,    builtMeshes_};
    auto takeShutter = [&] {
        if (!camera || camera->skipped()) return;
        ctx.shutterOpen = time + camera->params().shutterOpen;
        ctx.shutterClose = time + camera->params().shutterClose;
    };
    takeShutter();
    geometry_->prune();
    builtMeshes_.prune();
    // A failure half-way (the device out of memory) leaves every prim not synced to the end dirty,
    // so that a later render pulls it again.
    struct Requeue {
        std::vector<Prim*>& prims;
        std::set<Prim*>& dirty;
        ~Requeue() {
            for (Prim* prim : prims)
                if (prim->dirtyBits() != OBSCURA_DIRTY_CLEAN) {
                    prim->markDirty(OBSCURA_DIRTY_ALL);
                    dirty.insert(prim);
                }
        }
    } requeue{dirty, dirty_};
    // Rprims pull on several threads when the host says its callbacks allow it; sprims read
    // textures, which upload and log, on this thread.
    const bool parallel = sceneDelegate_.flags & OBSCURA_SCENE_DELEGATE_THREAD_SAFE;
    auto afterCamera = dirty.begin() + (!dirty.empty() && dirty.front() == camera ? 1 : 0);
    auto rprims = std::find_if(afterCamera, dirty.end(), [](const Prim* p) { return syncOrder(*p) == 1; });
    syncPrims({dirty.begin(), afterCamera}, ctx, false);
    takeShutter();
    syncPrims({afterCamera, rprims}, ctx, false);
    syncPrims({rprims, dirty.end()}, ctx, parallel);
    // Implicit surfaces, curves and NURBS patches refine with their size on screen: those whose level
    // changed are tessellated again, with the transforms and instance placements just synced.
    // The viewport's size, else the first bound render buffer's (checked when they are bound).
    uint32_t width = desc.viewport[2] > 0 ? uint32_t(desc.viewport[2]) : 0;
    uint32_t height = desc.viewport[3] > 0 ? uint32_t(desc.viewport[3]) : 0;
    const RenderBuffer* first = desc.aovBindingCount > 0 && desc.aovBindings[0].renderBufferPath
                                    ? find<RenderBuffer>(desc.aovBindings[0].renderBufferPath)
                                    : nullptr;
    if (width == 0 && first) width = first->width(), height = first->height();
    if (camera && !camera->skipped()) {
        const size_t refined = dirty.size();
        for (ViewDependentMesh* mesh : chooseViewDependentDetail(prims_, *camera, width, height)) dirty.push_back(mesh);
        syncPrims({dirty.begin() + std::ptrdiff_t(refined), dirty.end()}, ctx, parallel);
    }
    // All uploads of this sync go to the GPU in one submission.
    device_->flushUploads();
}

ObscuraStatus RenderDelegate::render(const ObscuraRenderPassDesc& desc) {
    if (desc.structSize < sizeof(ObscuraRenderPassDesc) || desc.sType != OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC)
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "ObscuraRenderPassDesc: wrong sType or structSize"};
    if (!deviceLost_.empty())
        throw ApiError{OBSCURA_ERROR_DEVICE, "the Vulkan device was lost (" + deviceLost_ +
                                                 "): destroy this delegate and create a new one"};
    if (!hasSceneDelegate_) throw ApiError{OBSCURA_ERROR_INVALID_STATE, "no scene delegate: call setSceneDelegate first"};
    if (!desc.cameraPath) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "render pass without a camera"};
    Camera* camera = find<Camera>(desc.cameraPath);
    if (!camera) throw ApiError{OBSCURA_ERROR_NOT_FOUND, std::string("no camera prim at ") + desc.cameraPath};
    if (desc.aovBindingCount > 0 && !desc.aovBindings)
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "aovBindings is NULL but aovBindingCount is not 0"};

    const RenderBufferLookup findBuffer = [this](const char* path) { return find<RenderBuffer>(path); };
    refuseMappedBuffers(desc, findBuffer);
    device_->context().faults().beginRender();
    auto syncStart = std::chrono::steady_clock::now();
    sync(desc.time, camera, desc);
    auto syncEnd = std::chrono::steady_clock::now();
    syncMilliseconds_ = std::chrono::duration<double, std::milli>(syncEnd - syncStart).count();
    if (camera->skipped()) throw ApiError{OBSCURA_ERROR_BAD_PRIM_DATA, "camera " + camera->problem()};

    AovBindings bindings =
        bindAovs(desc, findBuffer, *device_, device_->context().properties().limits.maxImageDimension2D);
    const uint32_t width = bindings.width, height = bindings.height;

    const renderer::FrameSettings& settings = settings_.values();
    if (std::string problem = frame_->updateDisplay(settings); !problem.empty())
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, problem};

    std::vector<std::string> ignoredDomes;
    const Light* dome = environmentDome(prims_, ignoredDomes);
    if (ignoredDomes != ignoredDomes_)
        for (const auto& path : ignoredDomes)
            log(OBSCURA_LOG_WARNING, path + ": only one textured dome is supported (" + dome->path() +
                                         " lights the scene); this one uses its constant colour");
    ignoredDomes_ = std::move(ignoredDomes);
    ShadowSettings shadows{settings.shadows, settings.shadowResolution, settings.shadowCascades};
    FrameSceneInputs frame{{}, prims_, *camera, width, height, settings.exposureStops, *textures_, shadows, dome};
    frame.domeBackdrop = settings.domeLightCameraVisibility;
    frame.includedPurposes = purposeMask(settings.includedPurposes);
    frame.pixelAspectRatio = settings.pixelAspectRatio;

    renderer::FrameRequest request;
    const CameraParams& cameraParams = camera->params();
    // XXX: the circle of confusion stays round in pixels when pixels are not square.
    request.camera = {desc.cameraPath,
                      width,
                      height,
                      camera->thinLens(double(width) * frame.pixelAspectRatio / double(height)),
                      camera->apertureShape(),
                      {cameraParams.clippingRange[0], cameraParams.clippingRange[1]},
                      desc.time,
                      {desc.time + cameraParams.shutterOpen, desc.time + cameraParams.shutterClose}};
    request.sceneVersion = sceneVersion_;
    request.drawnVersion = drawnVersion_;
    request.settingsVersion = settings_.version();
    request.environment = dome && dome->environment() ? dome->environment()->image : nullptr;
    request.aovs = std::move(bindings.requests);
    FrameSceneSource source(*device_, frame, sceneReport_, logSink_);
    frame_->render(source, request, settings);
    frameSetupMilliseconds_ = std::chrono::duration<double, std::milli>(frame_->recorded() - syncEnd).count();
    for (RenderBuffer* rb : bindings.targets) rb->setRendered(true);
    // Exported buffers go to the host's device: released to it, and the semaphore signalled.
    std::vector<gpu::BufferPtr> exported;
    for (RenderBuffer* rb : bindings.targets)
        if (rb->exported()) exported.push_back(rb->storage(*device_));
    if (!exported.empty()) exportTimeline_->release(exported);

    if (failOnValidation_ && device_->context().validationErrorCount() > 0)
        throw ApiError{OBSCURA_ERROR_VALIDATION, std::to_string(device_->context().validationErrorCount()) +
                                                     " Vulkan validation error(s); see the log"};
    for (const auto& [path, prim] : prims_)
        if (prim->skipped()) {
            lastError_ = "some prims were skipped because of bad data (first: " + prim->problem() + ")";
            return OBSCURA_ERROR_BAD_PRIM_DATA;
        }
    return OBSCURA_OK;
}

void RenderDelegate::map(const std::string& path, ObscuraMappedBuffer& out) {
    RenderBuffer* rb = find<RenderBuffer>(path);
    if (!rb) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no render buffer at " + path};
    if (!rb->rendered()) throw ApiError{OBSCURA_ERROR_INVALID_STATE, path + " has not been rendered"};
    if (rb->exported())
        throw ApiError{OBSCURA_ERROR_INVALID_STATE, path + " is exported: its pixels are in device memory the host imported"};
    out.width = rb->width();
    out.height = rb->height();
    out.format = rb->format();
    out.rowStride = rb->width() * rb->bytesPerPixel();
    out.data = rb->storage(*device_)->mapped();
    rb->mapped = true;
}

void RenderDelegate::exportBuffer(const std::string& path, ObscuraExternalBuffer& out) {
    RenderBuffer* rb = find<RenderBuffer>(path);
    if (!rb) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no render buffer at " + path};
    if (!rb->rendered()) throw ApiError{OBSCURA_ERROR_INVALID_STATE, path + " has not been rendered"};
    if (rb->mapped) throw ApiError{OBSCURA_ERROR_INVALID_STATE, path + " is mapped: unmap it before exporting it"};
    out.memoryFd = -1;
    out.semaphoreFd = -1;
    if (!device_->context().externalHandles().memoryFd)
        throw ApiError{OBSCURA_ERROR_DEVICE, device_->context().summary().name +
                                                 " cannot export memory (no VK_KHR_external_memory_fd): map the buffer"};
    if (!exportTimeline_) exportTimeline_ = std::make_unique<gpu::ExportTimeline>(*device_);
    rb->exportTo(*device_, *exportTimeline_, out);
}

void RenderDelegate::unmap(const std::string& path) {
    RenderBuffer* rb = find<RenderBuffer>(path);
    if (!rb) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no render buffer at " + path};
    rb->mapped = false;
}

void RenderDelegate::stats(ObscuraRenderStats& out) const {
    ObscuraRenderStats s{};
    s.sType = out.sType;
    s.pNext = out.pNext;
    s.structSize = out.structSize;
    s.primsSynced = primsSynced_;
    for (const auto& [path, prim] : prims_) s.primsSkipped += prim->skipped() ? 1u : 0u;
    s.validationErrors = device_->context().validationErrorCount();
    s.converged = frame_->converged() ? 1u : 0u;
    s.trianglesDrawn = sceneReport_.trianglesDrawn;
    s.syncMilliseconds = syncMilliseconds_;
    s.geometryBytes = geometry_->residentBytes();
    s.frameSetupMilliseconds = frameSetupMilliseconds_;
    std::snprintf(s.deviceName, sizeof(s.deviceName), "%s", device_->context().summary().name.c_str());
    out = s;
    fillChainedStats(out.pNext, {device_->memory(), sceneReport_.culling, exportTimeline_ ? exportTimeline_->value() : 0});
}

int32_t RenderDelegate::primId(const std::string& path) const {
    Mesh* mesh = find<Mesh>(path);
    if (!mesh) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no mesh at " + path};
    return mesh->primId();
}

}  // namespace obscura::delegate
