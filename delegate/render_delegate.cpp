#include "delegate/render_delegate.h"

#include "passes/clip_volumes.h"

#include "delegate/frame_scene_builder.h"
#include "delegate/reference_frames.h"
#include "gpu/vk_check.h"
#include "passes/accumulate.h"
#include "passes/aov_readback.h"
#include "passes/best_fit_normals.h"
#include "passes/depth_of_field.h"
#include "passes/edge_aa.h"
#include "passes/gbuffer.h"
#include "passes/lighting.h"
#include "passes/msaa_resolve.h"
#include "passes/motion_blur.h"
#include "passes/shadow_maps.h"
#include "passes/tonemap.h"
#include "passes/transparent.h"

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

struct AovInfo {
    const char* name;
    passes::Aov aov;
    ObscuraFormat format;
};
constexpr AovInfo kAovs[] = {
    {"color", passes::Aov::Color, OBSCURA_FORMAT_FLOAT32_VEC4},
    {"depth", passes::Aov::Depth, OBSCURA_FORMAT_FLOAT32},
    {"normal", passes::Aov::Normal, OBSCURA_FORMAT_FLOAT32_VEC3},
    {"albedo", passes::Aov::Albedo, OBSCURA_FORMAT_FLOAT32_VEC3},
    {"primId", passes::Aov::PrimId, OBSCURA_FORMAT_INT32},
    {"instanceId", passes::Aov::InstanceId, OBSCURA_FORMAT_INT32},
    {"display", passes::Aov::Display, OBSCURA_FORMAT_UNORM8_VEC4},
    {"motion", passes::Aov::Motion, OBSCURA_FORMAT_FLOAT32_VEC3},
};

const char* formatName(ObscuraFormat f) {
    switch (f) {
        case OBSCURA_FORMAT_FLOAT32_VEC4: return "float32Vec4";
        case OBSCURA_FORMAT_FLOAT32_VEC3: return "float32Vec3";
        case OBSCURA_FORMAT_FLOAT32: return "float32";
        case OBSCURA_FORMAT_INT32: return "int32";
        case OBSCURA_FORMAT_UNORM8_VEC4: return "unorm8Vec4";
        default: return "unknown";
    }
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
    options.log = [this](LogLevel level, const std::string& message) {
        log(level == LogLevel::Error     ? OBSCURA_LOG_ERROR
            : level == LogLevel::Warning ? OBSCURA_LOG_WARNING
            : level == LogLevel::Info    ? OBSCURA_LOG_INFO
                                         : OBSCURA_LOG_DEBUG,
            message);
    };
    auto context = gpu::Context::create(options);
    if (!context) throw ApiError{OBSCURA_ERROR_DEVICE, context.error()};
    device_ = std::make_unique<gpu::Device>(std::move(*context));
    pipelines_ = std::make_unique<passes::PipelineCache>(*device_);
    transients_ = std::make_unique<gpu::TransientImagePool>(*device_);
    timestamps_ = std::make_unique<gpu::Timestamps>(*device_);
    bestFitNormals_ = passes::createBestFitNormalsTexture(*device_);
    // With SSAO off the lighting pass reads one unoccluded texel.
    const uint8_t open = 255;
    const float farDepth = 0.0f;
    gpu::ImageDesc one;
    one.width = one.height = 1;
    one.format = passes::kSsaoAccessibilityFormat;
    unoccluded_.accessibility = device_->createTextureWithData(one, &open, sizeof(open), "ssao off");
    one.format = passes::kSsaoDepthFormat;
    unoccluded_.halfDepth = device_->createTextureWithData(one, &farDepth, sizeof(farDepth), "ssao off depth");
    const uint16_t still[2] = {0xFBFF, 0};  // half floats: kStaticVelocity (-65504), 0
    static_assert(passes::kStaticVelocity == -65504.0f);
    one.format = passes::kVelocityFormat;
    stillVelocity_ = device_->createTextureWithData(one, still, sizeof(still), "still velocity");
    textures_ = std::make_unique<TextureCache>(*device_, options.log);
    geometry_ = std::make_unique<GeometryCache>(*device_);
    environment_ = std::make_unique<EnvironmentCache>(*device_, textures_->sampler(WrapMode::Repeat, WrapMode::Clamp));
    log(OBSCURA_LOG_INFO, "device: " + device_->context().summary().name);
    if (!faultProblem.empty()) log(OBSCURA_LOG_WARNING, faultProblem);
}

RenderDelegate::~RenderDelegate() {
    vkDeviceWaitIdle(device_->vk());
    prims_.clear();
    environment_.reset();
    textures_.reset();
    geometry_.reset();
    bestFitNormals_.reset();
    unoccluded_ = {};
    stillVelocity_.reset();
    accumulation_ = {};
    msaaTaggedPixels_.reset();
    ssaoHistory_ = {};
    temporalAaHistory_ = {};
    shadowHistory_ = {};
    grading_ = passes::ColorGradingLut();
    timestamps_.reset();
    transients_.reset();
    pipelines_.reset();
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
    else if (type == "points") prim = std::make_unique<Points>(path, *schema, nextPrimId_++);
    else if (type == "camera") prim = std::make_unique<Camera>(path, *schema);
    else if (type == "distantLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Distant);
    else if (type == "sphereLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Sphere);
    else if (type == "rectLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Rect);
    else if (type == "diskLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Disk);
    else if (type == "domeLight") prim = std::make_unique<Light>(path, *schema, passes::LightType::Dome);
    else if (type == "material") prim = std::make_unique<Material>(path, *schema);
    else if (type == "renderBuffer") prim = std::make_unique<RenderBuffer>(path, *schema);
    else if (type == "instancer") prim = std::make_unique<Instancer>(path, *schema);
    else throw ApiError{OBSCURA_ERROR_UNKNOWN_TYPE, "prim type '" + type + "' has a schema but no implementation"};
    dirty_.insert(prim.get());
    prims_.emplace(path, std::move(prim));
    ++sceneVersion_;
}

void RenderDelegate::removePrim(const std::string& path) {
    // GPU resources the prim owns are retired: they die at the end of the next frame.
    auto it = prims_.find(path);
    if (it == prims_.end()) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no prim at " + path};
    dirty_.erase(it->second.get());
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
    }
}

VkSampleCountFlags RenderDelegate::offeredMsaaSampleCounts() const {
    const VkPhysicalDeviceLimits& limits = device_->context().properties().limits;
    return limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts &
           limits.framebufferStencilSampleCounts & limits.sampledImageColorSampleCounts &
           limits.sampledImageIntegerSampleCounts & limits.sampledImageDepthSampleCounts;
}

void RenderDelegate::setRenderSetting(const std::string& key, const ObscuraValue* value) {
    double previousRefineLevel = settings_.number("refineLevel");
    double previousTimeCodesPerSecond = settings_.number("timeCodesPerSecond");
    int32_t previousMsaa = int32_t(settings_.number("msaa"));
    std::string problem = settings_.set(key, value);
    if (!problem.empty())
        throw ApiError{findRenderSetting(key) ? OBSCURA_ERROR_INVALID_ARGUMENT : OBSCURA_ERROR_NOT_FOUND, problem};
    // A sample count the device does not offer is refused (not clamped: a host asking for 8 samples
    // and silently getting 4 would compare the wrong images), and the previous count stays.
    if (int32_t samples = int32_t(settings_.number("msaa")); key == "msaa" && samples != previousMsaa) {
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
    if (settings_.number("refineLevel") != previousRefineLevel)
        for (auto& [path, prim] : prims_)
            if (dynamic_cast<Mesh*>(prim.get())) markDirty(path, OBSCURA_DIRTY_TOPOLOGY);
    // Velocities are per second: another rate moves points and instances elsewhere in the shutter.
    if (settings_.number("timeCodesPerSecond") != previousTimeCodesPerSecond)
        for (auto& [path, prim] : prims_)
            if (dynamic_cast<Mesh*>(prim.get()) || dynamic_cast<Instancer*>(prim.get()))
                markDirty(path, OBSCURA_DIRTY_POINTS);
}

void RenderDelegate::sync(double time, const Camera* camera, const ObscuraRenderPassDesc& desc) {
    primsSynced_ = 0;
    // The camera's shutter decides the interval transforms are sampled over; sync it first.
    std::vector<Prim*> dirty(dirty_.begin(), dirty_.end());
    dirty_.clear();
    std::sort(dirty.begin(), dirty.end(), [camera](Prim* a, Prim* b) {
        int oa = a == camera ? -1 : syncOrder(*a), ob = b == camera ? -1 : syncOrder(*b);
        return oa != ob ? oa < ob : a->path() < b->path();
    });
    SyncContext ctx{sceneDelegate_, *device_, time, time, time, static_cast<int>(settings_.number("refineLevel")),
                    settings_.number("timeCodesPerSecond"), *textures_, *geometry_};
    auto takeShutter = [&] {
        if (!camera || camera->skipped()) return;
        ctx.shutterOpen = time + camera->params().shutterOpen;
        ctx.shutterClose = time + camera->params().shutterClose;
    };
    takeShutter();
    // A device failure (out of memory) leaves the prims not yet synced dirty, so that a later render
    // pulls them again.
    size_t next = 0;
    struct Requeue {
        std::vector<Prim*>& dirty;
        size_t& next;
        std::set<Prim*>& set;
        ~Requeue() {
            for (size_t i = next; i < dirty.size(); ++i) {
                dirty[i]->markDirty(OBSCURA_DIRTY_ALL);
                set.insert(dirty[i]);
            }
        }
    } requeue{dirty, next, dirty_};
    auto syncPrim = [&](Prim* prim) {
        prim->sync(ctx);
        if (prim == camera) takeShutter();
        ++primsSynced_;
        if (prim->skipped()) log(OBSCURA_LOG_ERROR, "skipped prim " + prim->problem());
        if (auto* mesh = dynamic_cast<Mesh*>(prim))
            for (const auto& w : mesh->warnings()) log(OBSCURA_LOG_WARNING, mesh->path() + ": " + w);
        if (auto* material = dynamic_cast<Material*>(prim))
            for (const auto& w : material->warnings()) log(OBSCURA_LOG_WARNING, material->path() + ": " + w);
        if (auto* light = dynamic_cast<Light*>(prim); light && !light->warning().empty())
            log(OBSCURA_LOG_WARNING, light->path() + ": " + light->warning());
        if (auto* cam = dynamic_cast<Camera*>(prim); cam && !cam->warning().empty())
            log(OBSCURA_LOG_WARNING, cam->path() + ": " + cam->warning());
    };
    for (; next < dirty.size(); ++next) syncPrim(dirty[next]);
    // Implicit surfaces, curves and points refine with their size on screen: those whose level
    // changed are tessellated again, with the transforms and instance placements just synced.
    // The viewport's size, else the first bound render buffer's (checked when they are bound).
    uint32_t width = desc.viewport[2] > 0 ? uint32_t(desc.viewport[2]) : 0;
    uint32_t height = desc.viewport[3] > 0 ? uint32_t(desc.viewport[3]) : 0;
    const RenderBuffer* first = desc.aovBindingCount > 0 && desc.aovBindings[0].renderBufferPath
                                    ? find<RenderBuffer>(desc.aovBindings[0].renderBufferPath)
                                    : nullptr;
    if (width == 0 && first) width = first->width(), height = first->height();
    if (camera && !camera->skipped())
        for (ViewDependentMesh* mesh : chooseViewDependentDetail(prims_, *camera, width, height)) syncPrim(mesh);
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

    // A mapped buffer keeps its contents until unmap: refuse before anything is pulled or drawn.
    for (uint32_t i = 0; i < desc.aovBindingCount; ++i)
        if (const char* path = desc.aovBindings[i].renderBufferPath)
            if (const RenderBuffer* rb = find<RenderBuffer>(path); rb && rb->mapped)
                throw ApiError{OBSCURA_ERROR_INVALID_STATE, std::string(path) + " is still mapped: unmap it before rendering"};
    device_->context().faults().beginRender();
    auto syncStart = std::chrono::steady_clock::now();
    sync(desc.time, camera, desc);
    auto syncEnd = std::chrono::steady_clock::now();
    syncMilliseconds_ = std::chrono::duration<double, std::milli>(syncEnd - syncStart).count();
    if (camera->skipped()) throw ApiError{OBSCURA_ERROR_BAD_PRIM_DATA, "camera " + camera->problem()};

    // Bind render buffers; they all share the viewport's size.
    std::vector<passes::AovRequest> requests;
    std::vector<RenderBuffer*> targets;
    const RenderBuffer* firstSkippedBuffer = nullptr;
    uint32_t width = desc.viewport[2] > 0 ? uint32_t(desc.viewport[2]) : 0;
    uint32_t height = desc.viewport[3] > 0 ? uint32_t(desc.viewport[3]) : 0;
    for (uint32_t i = 0; i < desc.aovBindingCount; ++i) {
        const ObscuraAovBinding& b = desc.aovBindings[i];
        if (!b.aov || !b.renderBufferPath) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "AOV binding with NULL names"};
        const AovInfo* info = nullptr;
        for (const auto& a : kAovs)
            if (std::strcmp(a.name, b.aov) == 0) info = &a;
        if (!info) throw ApiError{OBSCURA_ERROR_NOT_FOUND, std::string("unknown AOV '") + b.aov + "'"};
        RenderBuffer* rb = find<RenderBuffer>(b.renderBufferPath);
        if (!rb) throw ApiError{OBSCURA_ERROR_NOT_FOUND, std::string("no render buffer at ") + b.renderBufferPath};
        // A render buffer with bad data is a skipped prim like any other: the frame renders into the
        // others and render returns BAD_PRIM_DATA (it keeps its last pixels, or stays unrendered).
        if (rb->skipped()) {
            if (!firstSkippedBuffer) firstSkippedBuffer = rb;
            continue;
        }
        if (rb->format() != info->format)
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, std::string("AOV '") + b.aov + "' needs format " +
                                                               formatName(info->format) + ", " + b.renderBufferPath +
                                                               " is " + formatName(rb->format())};
        if (width == 0) width = rb->width(), height = rb->height();
        if (rb->width() != width || rb->height() != height)
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, std::string(b.renderBufferPath) +
                                                               " does not match the viewport size"};
        requests.push_back({info->aov, rb->storage(*device_), rb->deviceStaging(*device_)});
        targets.push_back(rb);
    }
    if ((width == 0 || height == 0) && firstSkippedBuffer)
        throw ApiError{OBSCURA_ERROR_BAD_PRIM_DATA, "no size to render at: render buffer " + firstSkippedBuffer->problem()};
    if (width == 0 || height == 0) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "empty viewport and no render buffers"};
    const uint32_t maxSize = device_->context().properties().limits.maxImageDimension2D;
    if (width > maxSize || height > maxSize)
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "viewport " + std::to_string(width) + "x" + std::to_string(height) +
                                                           " exceeds " + std::to_string(maxSize) +
                                                           " pixels a side, the device's largest image"};

    passes::ColorLutRequest colour{settings_.token("ocio:config"), settings_.token("ocio:display"),
                                   settings_.token("ocio:view"), settings_.token("ocio:look")};
    if (std::string problem = gradingChart_.load(settings_.token("grading:chart")); !problem.empty())
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "colour grading: " + problem};
    passes::DisplayGrade grade{gradingChart_.lattice(),
                                         settings_.token("grading:interpolation") == "tetrahedral"
                                             ? passes::LatticeInterpolation::Tetrahedral
                                             : passes::LatticeInterpolation::Trilinear,
                                         gradingChart_.key()};
    if (std::string problem = grading_.update(*device_, colour, grade); !problem.empty())
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "colour management: " + problem};

    std::vector<std::string> ignoredDomes;
    const Light* dome = environmentDome(prims_, ignoredDomes);
    if (ignoredDomes != ignoredDomes_)
        for (const auto& path : ignoredDomes)
            log(OBSCURA_LOG_WARNING, path + ": only one textured dome is supported (" + dome->path() +
                                         " lights the scene); this one uses its constant colour");
    ignoredDomes_ = std::move(ignoredDomes);
    ShadowSettings shadows{settings_.number("shadows") != 0.0, uint32_t(settings_.number("shadows:resolution")),
                           uint32_t(settings_.number("shadows:cascades"))};
    FrameSceneInputs frame{prims_, *camera, width, height, settings_.number("exposure"), *textures_, shadows, dome};
    frame.domeBackdrop = settings_.number("domeLightCameraVisibility") != 0.0;
    frame.includedPurposes = purposeMask(settings_.token("includedPurposes"));
    frame.pixelAspectRatio = settings_.number("pixelAspectRatio");
    // The `dof` setting turns the lens off for the post-process and the reference alike, and
    // `motionBlur` the shutter.
    // XXX: the circle of confusion stays round in pixels when pixels are not square.
    passes::ThinLens lens = settings_.number("dof") != 0.0 ? camera->thinLens(double(width) * frame.pixelAspectRatio / double(height))
                                                           : passes::ThinLens{};
    const CameraParams& cameraParams = camera->params();
    std::array<double, 2> shutter{desc.time, desc.time};
    if (settings_.number("motionBlur") != 0.0 && cameraParams.shutterClose > cameraParams.shutterOpen)
        shutter = {desc.time + cameraParams.shutterOpen, desc.time + cameraParams.shutterClose};
    uint32_t referenceSubFrames = static_cast<uint32_t>(settings_.number("reference"));
    const PixelFilter pixelFilter{pixelFilterKind(settings_.token("pixelFilter")), settings_.number("pixelFilter:width")};
    if (referenceSubFrames > 0) accumulateReference(frame, lens, referenceSubFrames, shutter, pixelFilter);
    else if (shutter[1] > shutter[0]) frame.shutter = shutter;

    // Temporal AA picks this frame's jitter before the scene's camera constants are packed. The
    // reference is its own ground truth, jittered per sub-frame: no temporal AA there.
    std::optional<TemporalAaStep> temporalAa;
    passes::TemporalAaSettings temporalAaSettings{
        settings_.token("taa:mode") == "2tx" ? passes::TemporalAaMode::Smaa2tx : passes::TemporalAaMode::Smaa1tx,
        float(settings_.number("taa:kLowFreq")), float(settings_.number("taa:kHighFreq"))};
    if (settings_.number("taa") != 0.0 && referenceSubFrames == 0) {
        FrameView seen = frameView(frame);
        temporalAa = temporalAccumulation_.next({desc.cameraPath, width, height, settings_.version()}, sceneVersion_,
                                                temporalAaSettings.mode, uint32_t(settings_.number("taa:frames")),
                                                seen.view, seen.projection,
                                                {frame.shutter.has_value(), passes::hasDepthOfField(lens),
                                                 1.0 / std::sqrt(settings_.number("msaa")), pixelFilter});
        frame.clipJitter = temporalAa->clipJitter;
        if (temporalAa->shutterStratum) frame.shutterSpan = *temporalAa->shutterStratum;
        if (temporalAa->lensStratum) {
            // The accumulation-buffer camera's lens, as the reference spreads its sub-frames.
            double apertureRadius = 0.5 * passes::accumulationApertureDiameter(lens);
            auto onAperture = stillApertureSample(*temporalAa->lensStratum, temporalAa->pass.framesToConverge,
                                                  camera->apertureShape());
            frame.lensOffset = {onAperture[0] * apertureRadius, onAperture[1] * apertureRadius};
        }
        frame.noiseFrame = temporalAa->noiseFrame;
        frame.linearResolve = temporalAa->pass.unchanged;
        // Hybrid AA (seed 004) while anything changes; a still accumulates jittered frames of every
        // object, converging to the supersampled image, which edge AA never reaches.
        if (temporalAaSettings.mode == passes::TemporalAaMode::Smaa1tx && !temporalAa->pass.unchanged)
            frame.edgeAaDistance = settings_.number("taa:hybridDistance") / settings_.number("metersPerUnit");
    } else {
        temporalAccumulation_.reset();
    }

    // Temporal AA reprojects what moved since the last frame along its own motion.
    InstanceModels models;
    if (temporalAa) {
        frame.lastModels = &lastModels_;
        frame.models = &models;
    }
    FrameSceneShortfalls shortfalls;
    passes::FrameScene scene = buildFrameScene(*device_, frame, shortfalls);
    lastModels_ = std::move(models);
    if (shortfalls.lightsWithoutShadowRoom != lightsWithoutShadowRoom_ && shortfalls.lightsWithoutShadowRoom > 0)
        log(OBSCURA_LOG_WARNING, std::to_string(shortfalls.lightsWithoutShadowRoom) +
                                     " light(s) cast no shadow: the shadow atlas is full (lower shadows:resolution)");
    lightsWithoutShadowRoom_ = shortfalls.lightsWithoutShadowRoom;
    if (shortfalls.unclippedLights != unclippedLights_)
        for (const auto& problem : shortfalls.unclippedLights) log(OBSCURA_LOG_WARNING, problem);
    unclippedLights_ = shortfalls.unclippedLights;
    if (scene.instanceCount > passes::kMaxInstanceRecords)
        throw ApiError{OBSCURA_ERROR_OUT_OF_MEMORY, std::to_string(scene.instanceCount) +
                                                        " instances: the G-buffer addresses at most " +
                                                        std::to_string(passes::kMaxInstanceRecords)};
    trianglesDrawn_ = 0;
    for (const auto& d : scene.draws) trianglesDrawn_ += uint64_t(d.indexCount / 3) * d.instanceCount;

    // The frame (DESIGN.md "The frame"): shadow maps, G-buffer, clip volumes into stencil, SSAO,
    // lighting, temporal AA, depth of field, tone mapping, AOV readback. In reference mode the
    // accumulated sub-frames replace all between the G-buffer and tone mapping; the other AOVs come
    // from the pinhole camera.
    // With msaa > 1 the G-buffer is multisampled and the custom resolve hands the single-sample
    // one to everything after it; the lighting pass alone reads the samples (seed 000 "Deferred
    // MSAA"). Reference mode's sub-frames carry their own pixel jitter, so it renders one sample.
    gpu::FrameGraph graph;
    gpu::ImageHandle shadowAtlas;
    shadowHistory_.importedInto = nullptr;  // a failed frame's import is not this graph's
    if (referenceSubFrames == 0) shadowAtlas = passes::addShadowMapPass(graph, *pipelines_, scene, &shadowHistory_);
    auto samples = VkSampleCountFlagBits(referenceSubFrames == 0 ? uint32_t(settings_.number("msaa")) : 1u);
    passes::GBuffer gbuffer = passes::addGBufferPass(graph, *pipelines_, scene, bestFitNormals_, samples,
                                                     settings_.number("msaa:alphaToCoverage") != 0.0);
    std::optional<MsaaFrame> msaa;
    if (samples != VK_SAMPLE_COUNT_1_BIT) {
        if (!msaaTaggedPixels_)
            msaaTaggedPixels_ = device_->createBuffer(sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                      gpu::MemoryUsage::Readback, "msaa tagged pixels");
        *static_cast<uint32_t*>(msaaTaggedPixels_->mapped()) = 0;
        passes::PerSampleLighting perSample{gbuffer, graph.importBuffer("msaaTaggedPixels", msaaTaggedPixels_)};
        graph.markOutput(perSample.taggedPixelCount);
        passes::MsaaResolve resolve = passes::addMsaaResolvePass(graph, *pipelines_, scene, gbuffer);
        gbuffer = resolve.resolved;
        msaa = MsaaFrame{perSample, resolve.maxDepth};
    }
    gpu::ImageHandle hdr;
    gpu::ImageHandle transparentCoverage;
    bool dofAfterTemporalAa = false;
    if (referenceSubFrames > 0) {
        gpu::ImageHandle sum = graph.importImage("referenceAccumulation", accumulation_.image, accumulation_.layout);
        hdr = passes::addAccumulationResolvePass(graph, *pipelines_, sum,
                                                 lightAccumulation() == passes::LightAccumulation::HalfFloat
                                                     ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                     : VK_FORMAT_B10G11R11_UFLOAT_PACK32);
        // The sub-frames blended the transparent surfaces into the accumulation. XXX: the alpha of
        // the reference's colour is the pinhole G-buffer's coverage alone (this clears the
        // transparent coverage): transparents over the background are not in it.
        transparentCoverage = passes::addTransparentPass(graph, *pipelines_, scene, {}, gbuffer.depth, hdr, {}, {}, {});
    } else {
        hdr = addLighting(graph, scene, gbuffer, shadowAtlas, frame, transparentCoverage, msaa ? &*msaa : nullptr);
        const int motionBlurSamples = static_cast<int>(settings_.number("motionBlur:samples"));
        // A still's sample of the shutter is blurred over its stratum alone, before it joins the
        // mean: the post-process fills only what lies between the samples' times.
        const bool stratumBlur = scene.motionBlur && temporalAa && temporalAa->shutterStratum;
        // A still's sample of the lens likewise is blurred over its stratum of the aperture alone:
        // 1/N of the aperture's area, a circle of confusion 1/sqrt(N) as wide.
        const bool lensSample = temporalAa && temporalAa->lensStratum;
        auto depthOfField = [&](double cocShare) {
            passes::CocFromDepth coc = passes::cocFromDepth(lens, cameraParams.clippingRange[0],
                                                            cameraParams.clippingRange[1], double(width));
            coc.scale *= cocShare;
            coc.bias *= cocShare;
            return passes::DepthOfFieldSettings{coc, camera->apertureShape(), static_cast<int>(settings_.number("dof:taps"))};
        };
        if (stratumBlur || lensSample) {
            hdr = passes::addTemporalAaSamplePass(graph, *pipelines_, scene, gbuffer, hdr, transparentCoverage);
            if (lensSample)
                hdr = passes::addDepthOfFieldPasses(
                    graph, *pipelines_, scene, gbuffer, hdr,
                    depthOfField(1.0 / std::sqrt(double(temporalAa->pass.framesToConverge))));
            if (stratumBlur) hdr = passes::addMotionBlurPasses(graph, *pipelines_, scene, gbuffer, hdr, motionBlurSamples);
            temporalAa->pass.colorHasCoverage = true;
        }
        if (temporalAa) {
            temporalAa->pass.edgeAa = scene.edgeAa;
            hdr = passes::addTemporalAaPass(graph, *pipelines_, scene, gbuffer, hdr, transparentCoverage,
                                            temporalAaSettings, temporalAa->pass, temporalAaHistory_);
            temporalAaInFrame_ = true;
            if (scene.edgeAa) hdr = passes::addEdgeAaPasses(graph, *pipelines_, scene, gbuffer, hdr);
        }
        // Over the whole aperture, unless the still's mean holds it, sample by sample.
        dofAfterTemporalAa = passes::hasDepthOfField(lens) && !lensSample && !(temporalAa && temporalAa->lensAccumulated);
        if (dofAfterTemporalAa)
            hdr = passes::addDepthOfFieldPasses(graph, *pipelines_, scene, gbuffer, hdr, depthOfField(1.0));
        // After depth of field (seed 000 "MB or DOF first?": motion blur gathers with the
        // geometry's depth and velocity, and is the error less seen when it comes last), over the
        // whole shutter: unless the still's mean already holds it, sample by sample.
        if (scene.motionBlur && !stratumBlur && !(temporalAa && temporalAa->shutterAccumulated))
            hdr = passes::addMotionBlurPasses(graph, *pipelines_, scene, gbuffer, hdr, motionBlurSamples);
    }
    // Temporal AA's accumulation carries coverage in alpha, and motion blur blurs it along; depth of
    // field keeps a sample's coverage where it runs before the mean, and writes none after it.
    passes::HdrAlpha hdrAlpha = passes::HdrAlpha::None;
    if (temporalAa && !dofAfterTemporalAa) hdrAlpha = passes::HdrAlpha::Coverage;
    gpu::ImageHandle display = passes::addTonemapPass(graph, *pipelines_, scene, hdr, hdrAlpha, gbuffer.instance,
                                                      transparentCoverage, grading_);
    gpu::ImageHandle velocity =
        gbuffer.velocity.valid()
            ? gbuffer.velocity
            : graph.importImage("velocity.still", stillVelocity_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    passes::addAovReadbackPass(graph, *pipelines_, scene, gbuffer, hdr, hdrAlpha, transparentCoverage, display,
                               velocity, requests);
    executeFrame(graph);
    converged_ = !temporalAa || temporalAa->converged;
    if (msaa) {
        // Issue 5: the share of pixels the per-sample mask sends to sample-frequency lighting.
        uint32_t tagged = *static_cast<const uint32_t*>(msaaTaggedPixels_->mapped());
        char line[160];
        std::snprintf(line, sizeof(line), "msaa %ux: %.2f%% of pixels tagged for per-sample lighting (%u of %u)",
                      uint32_t(samples), 100.0 * tagged / (double(width) * height), tagged, width * height);
        log(OBSCURA_LOG_INFO, line);
    }
    frameSetupMilliseconds_ = std::chrono::duration<double, std::milli>(frameRecorded_ - syncEnd).count();
    for (RenderBuffer* rb : targets) rb->setRendered(true);

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

gpu::ImageHandle RenderDelegate::addLighting(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                             const passes::GBuffer& gbuffer, gpu::ImageHandle shadowAtlas,
                                             const FrameSceneInputs& frame, gpu::ImageHandle& transparentCoverage,
                                             const MsaaFrame* msaa) {
    FrameView seen = frameView(frame);
    passes::addClipVolumePass(graph, *pipelines_, scene, gbuffer);
    passes::SsaoResult ambient;
    const bool ssaoOn = settings_.number("ssao") != 0.0;
    if (ssaoOn) {
        // The radius is authored in metres; the passes work in scene units (USD metersPerUnit).
        passes::SsaoSettings ssao{float(settings_.number("ssao:radius") / settings_.number("metersPerUnit")),
                                  float(settings_.number("ssao:intensity"))};
        // The history reprojects through the camera's motion; anything else that changes what a
        // texel means (size, projection, settings) restarts it.
        auto& last = ssaoHistoryFrame_;
        ssaoHistory_.valid = last.valid && last.width == scene.width && last.height == scene.height &&
                             last.projection == seen.projection && last.settingsVersion == settings_.version();
        Matrix4d inverseView = kIdentity;
        invert(seen.view, inverseView);
        ssaoHistory_.viewToPreviousView = toFloats<passes::Mat4>(multiply(inverseView, last.view));
        ambient = passes::addSsaoPasses(graph, *pipelines_, scene, gbuffer, ssao, ssaoHistory_);
        ssaoInFrame_ = true;
    } else {
        ambient = {graph.importImage("ssao.off", unoccluded_.accessibility, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL),
                   graph.importImage("ssao.off.depth", unoccluded_.halfDepth, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)};
    }
    ssaoHistoryFrame_ = {ssaoOn, seen.view, seen.projection, scene.width, scene.height, settings_.version()};
    const Light* dome = frame.environmentDome;
    passes::EnvironmentLighting environment =
        environment_->addToFrame(graph, *pipelines_, dome ? dome->environment() : nullptr);
    environmentInFrame_ = true;
    gpu::ImageHandle hdr = passes::addLightingPass(graph, *pipelines_, scene, gbuffer, ambient, shadowAtlas,
                                                   environment, lightAccumulation(), msaa ? &msaa->perSample : nullptr);
    // Transparent surfaces over the lit opaque ones, before temporal AA (DESIGN.md "The frame").
    // The fade distance is authored in metres, like the SSAO radius.
    passes::TransparentSettings transparents{
        float(settings_.number("transparents:fadeDistance") / settings_.number("metersPerUnit"))};
    transparentCoverage =
        passes::addTransparentPass(graph, *pipelines_, scene, scene.transparentDraws, msaa ? msaa->maxDepth : gbuffer.depth,
                                   hdr, shadowAtlas, environment, transparents);
    return hdr;
}

passes::LightAccumulation RenderDelegate::lightAccumulation() const {
    return settings_.number("lighting:halfFloat") != 0.0 ? passes::LightAccumulation::HalfFloat
                                                         : passes::LightAccumulation::SmallFloat;
}

void RenderDelegate::executeFrame(gpu::FrameGraph& graph) {
    graph.compile();
    if (environmentInFrame_) environment_->frameCompiled(graph);
    environmentInFrame_ = false;
    if (ssaoInFrame_) passes::keepSsaoHistory(graph, ssaoHistory_);
    if (temporalAaInFrame_) passes::keepTemporalAaHistory(graph, temporalAaHistory_);
    passes::keepShadowAtlasHistory(graph, shadowHistory_);
    ssaoInFrame_ = temporalAaInFrame_ = false;
    device_->context().submitAndWait([&](VkCommandBuffer cmd) {
        timestamps_->reset(cmd);
        graph.execute(*transients_, cmd, timestamps_.get());
        frameRecorded_ = std::chrono::steady_clock::now();
    });
    timings_ = timestamps_->resolve();
    device_->endFrame();
    transients_->endFrame();
}

void RenderDelegate::accumulateReference(const FrameSceneInputs& frame, const passes::ThinLens& lens, uint32_t count,
                                         const std::array<double, 2>& shutter, const PixelFilter& pixelFilter) {
    const gpu::ImageDesc* current = accumulation_.image ? &accumulation_.image->desc : nullptr;
    if (!current || current->width != frame.width || current->height != frame.height) {
        gpu::ImageDesc desc;
        desc.format = passes::kAccumulationFormat;
        desc.width = frame.width;
        desc.height = frame.height;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        accumulation_ = {device_->createImage(desc, "reference accumulation"), VK_IMAGE_LAYOUT_UNDEFINED};
    }
    // Without depth of field the lens is a pinhole: every sub-frame looks from its centre.
    bool lensBlur = passes::hasDepthOfField(lens);
    double apertureRadius = 0.5 * passes::accumulationApertureDiameter(lens);
    const auto [open, close] = shutter;
    std::vector<ReferenceSubFrame> subFrames =
        referenceSubFrames(count, lensBlur ? frame.camera.apertureShape() : passes::ApertureShape{}, pixelFilter);
    for (size_t k = 0; k < subFrames.size(); ++k) {
        const ReferenceSubFrame& sub = subFrames[k];
        FrameSceneInputs inputs = frame;
        if (close > open) inputs.shutter = shutter;
        inputs.sample = FrameSample{open + sub.shutter * (close - open),
                                    {sub.aperture[0] * apertureRadius, sub.aperture[1] * apertureRadius},
                                    sub.pixelJitter, sub.emitter};
        FrameSceneShortfalls shortfalls;  // reported by the frame itself
        passes::FrameScene scene = buildFrameScene(*device_, inputs, shortfalls);
        gpu::FrameGraph graph;
        gpu::ImageHandle shadowAtlas = passes::addShadowMapPass(graph, *pipelines_, scene);
        passes::GBuffer gbuffer = passes::addGBufferPass(graph, *pipelines_, scene, bestFitNormals_);
        // Each sub-frame blends its transparent surfaces into its lighting; their coverage is not kept.
        gpu::ImageHandle transparentCoverage;
        gpu::ImageHandle hdr = addLighting(graph, scene, gbuffer, shadowAtlas, inputs, transparentCoverage);
        gpu::ImageHandle sum = graph.importImage("referenceAccumulation", accumulation_.image, accumulation_.layout);
        passes::addAccumulatePass(graph, *pipelines_, hdr, sum, float(sub.weight), k == 0);
        executeFrame(graph);
        accumulation_.layout = graph.finalLayout(sum);
    }
}

void RenderDelegate::map(const std::string& path, ObscuraMappedBuffer& out) {
    RenderBuffer* rb = find<RenderBuffer>(path);
    if (!rb) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no render buffer at " + path};
    if (!rb->rendered()) throw ApiError{OBSCURA_ERROR_INVALID_STATE, path + " has not been rendered"};
    out.width = rb->width();
    out.height = rb->height();
    out.format = rb->format();
    out.rowStride = rb->width() * rb->bytesPerPixel();
    out.data = rb->storage(*device_)->mapped();
    rb->mapped = true;
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
    s.converged = converged_ ? 1u : 0u;
    s.trianglesDrawn = trianglesDrawn_;
    s.syncMilliseconds = syncMilliseconds_;
    s.geometryBytes = geometry_->residentBytes();
    s.frameSetupMilliseconds = frameSetupMilliseconds_;
    std::snprintf(s.deviceName, sizeof(s.deviceName), "%s", device_->context().summary().name.c_str());
    out = s;
    // Output structs chain Vulkan style; the header is const only because input structs share it.
    for (auto* next = static_cast<const ObscuraStructHeader*>(out.pNext); next;
         next = static_cast<const ObscuraStructHeader*>(next->pNext)) {
        if (next->sType == OBSCURA_STRUCTURE_TYPE_MEMORY_STATS && next->structSize >= sizeof(ObscuraMemoryStats)) {
            auto* memory = const_cast<ObscuraMemoryStats*>(reinterpret_cast<const ObscuraMemoryStats*>(next));
            const gpu::MemoryAllocator& allocator = device_->memory();
            memory->deviceMemoryReserved = allocator.bytesReserved();
            memory->deviceMemoryInUse = allocator.bytesInUse();
            memory->deviceMemoryBlocks = uint32_t(allocator.blockCount());
        }
    }
}

int32_t RenderDelegate::primId(const std::string& path) const {
    Mesh* mesh = find<Mesh>(path);
    if (!mesh) throw ApiError{OBSCURA_ERROR_NOT_FOUND, "no mesh at " + path};
    return mesh->primId();
}

}  // namespace obscura::delegate
