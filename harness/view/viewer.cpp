#include "harness/view/viewer.h"

#include "harness/exit_codes.h"
#include "harness/view/render_buffer_display.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace obscura::harness::view {

void Viewer::insertBuffers(int width, int height) {
    width_ = width;
    height_ = height;
    scene_.aspect = double(width) / double(height);
    auto bind = [&](const std::string& name, const std::string& aov) {
        std::string path = scene_.renderBuffer(name, aov, width, height);
        if (buffers_.count(name)) session_.api().markDirty(session_.delegate(), path.c_str(), OBSCURA_DIRTY_PARAMS);
        else session_.api().insertPrim(session_.delegate(), "renderBuffer", path.c_str());
        buffers_[name] = path;
    };
    bind("shown", aov_);
    for (const char* aov : kPickAovs) bind(aov, aov);
    source_.reset();
    exportPending_ = o_.display != "readback";
    cameraChanged();
}

bool Viewer::setup() {
    const ObscuraApiV1& api = session_.api();
    if (api.setSceneDelegate(session_.delegate(), &scene_.sceneDelegate()) != OBSCURA_OK ||
        api.insertPrim(session_.delegate(), "camera", ViewerScene::kCameraPath) != OBSCURA_OK) {
        std::fprintf(stderr, "obscura: %s\n", session_.lastError().c_str());
        return false;
    }
    for (const auto& [path, type] : session_.host().insertedPrims())
        if (type == "camera") sceneCameras_.push_back(path);
    time_ = session_.stage().metadata().startTimeCode.value_or(0.0);
    scene_.camera = OrbitCamera(session_.stage().metadata().upAxis);
    const SceneBounds bounds = session_.host().bounds(time_);
    int width = 0, height = 0;
    window_.framebufferSize(width, height);
    scene_.aspect = double(width) / double(height);
    scene_.camera.frame(bounds.centre, bounds.radius,
                        std::min(scene_.verticalFov(), 2 * std::atan(std::tan(0.5 * scene_.verticalFov()) * scene_.aspect)));
    scene_.lens.focusDistance = scene_.camera.distance();
    scene_.lens.nearClip = std::max(scene_.camera.distance() - 4.0 * bounds.radius, scene_.camera.distance() * 1e-3);
    scene_.lens.farClip = scene_.camera.distance() + 100.0 * bounds.radius;
    if (!o_.camera.empty()) {
        auto it = std::find(sceneCameras_.begin(), sceneCameras_.end(), o_.camera);
        if (it == sceneCameras_.end()) {
            std::fprintf(stderr, "obscura: %s is not a camera of the scene\n", o_.camera.c_str());
            return false;
        }
        cameraIndex_ = int(it - sceneCameras_.begin()) + 1;
    } else if (!sceneCameras_.empty()) {
        cameraIndex_ = 1;  // as `obscura render`: the stage's first camera
    }
    // The settings' defaults: depth of field and motion blur on where the camera asks for them.
    for (const char* effect : kEffects) effects_[effect] = true;
    insertBuffers(width, height);
    reload_.emplace(session_);
    return true;
}

bool Viewer::createDisplay() {
    DisplayDeviceOptions options;
    options.validation = o_.validation;
    options.instanceExtensions = window_.instanceExtensions();
    options.swapchain = true;
    options.deviceName = session_.deviceName();
    auto created = DisplayDevice::create(options);
    if (auto* problem = std::get_if<std::string>(&created)) {
        std::fprintf(stderr, "obscura: %s\n", problem->c_str());
        return false;
    }
    display_ = std::move(std::get<std::unique_ptr<DisplayDevice>>(created));
    window_.attach(*display_);
    image_ = std::make_unique<AovImage>(*display_);
    return true;
}

bool Viewer::updateSource(bool& exportedNow) {
    exportedNow = false;
    if (exportPending_) {
        exportPending_ = false;
        // Whether the display device can import is asked first: an exported buffer cannot be mapped.
        auto exported = display_->canImport()
                             ? exportRenderBuffer(session_, buffers_["shown"])
                             : std::variant<ObscuraExternalBuffer, std::string>(display_->name() + " cannot import memory");
        if (auto* external = std::get_if<ObscuraExternalBuffer>(&exported)) {
            auto imported = DisplaySource::import(*display_, *external);
            if (auto* problem = std::get_if<std::string>(&imported)) {
                std::fprintf(stderr, "obscura: %s\n", problem->c_str());
                return false;
            }
            source_ = std::move(std::get<std::unique_ptr<DisplaySource>>(imported));
            exportedNow = true;
            return true;
        }
        if (o_.display == "shared") {
            std::fprintf(stderr, "obscura: the render buffer cannot be shared: %s\n",
                         std::get<std::string>(exported).c_str());
            return false;
        }
    }
    if (source_ && source_->shared()) return true;
    if (std::string problem = copyRenderBuffer(session_, *display_, buffers_["shown"], source_); !problem.empty()) {
        std::fprintf(stderr, "obscura: %s\n", problem.c_str());
        return false;
    }
    return true;
}

bool Viewer::render(bool withPick) {
    std::vector<ObscuraAovBinding> bindings = {{aov_.c_str(), buffers_["shown"].c_str()}};
    if (withPick)
        for (const char* aov : kPickAovs) bindings.push_back({aov, buffers_[aov].c_str()});
    ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(desc), activeCamera(),
                               {0, 0, width_, height_}, time_, uint32_t(bindings.size()), bindings.data()};
    ObscuraStatus status = session_.api().render(session_.delegate(), &desc);
    if (status != OBSCURA_OK && status != OBSCURA_ERROR_BAD_PRIM_DATA) {
        std::fprintf(stderr, "obscura: render failed: %s\n", session_.lastError().c_str());
        return false;
    }
    accumulated_ = changed_ ? 1 : accumulated_ + 1;
    changed_ = false;
    const ObscuraRenderStats stats = session_.renderStats();
    converged_ = stats.converged != 0;
    if (reportSync_) {
        reportSync_ = false;
        std::printf("synced %u prim%s after the reload\n", stats.primsSynced, stats.primsSynced == 1 ? "" : "s");
        std::fflush(stdout);
    }
    if (!display_ && !createDisplay()) return false;
    bool exportedNow = false;
    if (!updateSource(exportedNow)) return false;
    // The exported memory holds frames from the next render on.
    if (exportedNow) return render(withPick);
    showSource(session_, *display_, *source_, *image_, aovViewOf(aov_));
    return true;
}

void Viewer::watchFiles() {
    if (!reload_->filesChanged()) return;
    std::optional<size_t> touched = reload_->reload(session_, scene_, o_.scene, o_.stage, time_);
    if (!touched) return;
    waitReload_ = false;
    if (*touched) changed_ = reportSync_ = true;
}

int Viewer::run() {
    if (!o_.script.empty()) {
        auto read = readInputScript(o_.script);
        if (auto* problem = std::get_if<std::string>(&read)) {
            std::fprintf(stderr, "obscura: %s\n", problem->c_str());
            return kExitUsage;
        }
        script_ = std::get<std::vector<ScriptEvent>>(read);
    }
    if (!setup()) return kExitPluginOrDevice;
    listen();
    GLFWwindow* w = window_.glfw();
    while (!glfwWindowShouldClose(w)) {
        // Progressive: a frame whenever something changed, then temporal AA accumulates until it
        // has converged; after that the window only waits for input (or the scene's files).
        const bool scriptWaits = scriptAt_ >= script_.size() || waitReload_;
        if (converged_ && !changed_ && scriptWaits) glfwWaitEventsTimeout(0.25);
        else glfwPollEvents();
        if (!playScript()) return kExitUsage;
        watchFiles();
        int width = 0, height = 0;
        window_.framebufferSize(width, height);
        if (width > 0 && height > 0 && (width != width_ || height != height_)) insertBuffers(width, height);
        if (changed_ || !converged_) {
            if (!render(false)) return kExitPluginOrDevice;
            if (framesLeft_ > 0) --framesLeft_;
        }
        if (!image_) continue;
        buildHud();
        window_.present(*image_, hud_, "");
    }
    return kExitOk;
}

}  // namespace obscura::harness::view
