// obscura view SCENE: the interactive viewer. A host of the plugin like the other commands (the
// scene read by the harness, prims inserted through the ABI), with a camera of its own, a window
// that shows the render buffers without reading them back where the plugin exports them (ABI
// 1.2), a HUD, picking and reloading of the scene's files when they change on disk.
#include "harness/aov_output.h"
#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/session.h"
#include "harness/view/display_device.h"
#include "harness/view/input_script.h"
#include "harness/view/viewer_scene.h"
#include "harness/view/viewer_window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

namespace obscura::harness {
namespace {

namespace fs = std::filesystem;
using view::AovView;
using view::ViewerScene;

// Effects the HUD and the keys toggle (render settings, named as in `obscura info`).
constexpr const char* kEffects[] = {"taa", "ssao", "shadows", "dof", "motionBlur"};
constexpr const char* kAovs[] = {"display", "depth", "normal", "motion", "primId"};

ObscuraRenderStats statsOf(const Session& session, ObscuraInteropStats* interop = nullptr) {
    ObscuraRenderStats stats{};
    stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
    stats.structSize = sizeof(stats);
    if (interop) {
        *interop = {OBSCURA_STRUCTURE_TYPE_INTEROP_STATS, nullptr, sizeof(ObscuraInteropStats), 0};
        stats.pNext = interop;
    }
    session.api().getRenderStats(session.delegate(), &stats);
    return stats;
}

// The files a stage was read from (where its prims and attributes are authored), with their times.
std::map<std::string, fs::file_time_type> sceneFiles(const usda::Stage& stage) {
    std::map<std::string, fs::file_time_type> files;
    auto add = [&](const std::string& file) {
        std::error_code ec;
        // A layer inside a package is watched through the package.
        std::string path = file.substr(0, file.find('['));
        if (path.empty() || files.count(path)) return;
        auto time = fs::last_write_time(path, ec);
        if (!ec) files[path] = time;
    };
    for (const usda::Prim* prim : stage.prims()) {
        add(prim->where.file);
        for (const auto& [name, attribute] : prim->attributes) add(attribute.where.file);
    }
    return files;
}

class Viewer {
public:
    Viewer(const ViewOptions& options, Session& session, view::ViewerWindow& window)
        : o_(options), session_(session), window_(window), scene_(session.host()) {}

    int run();
    // Releases every Vulkan object of the viewer: the window's, the image's, the imported memory,
    // then the display device.
    void close() {
        source_.reset();
        image_.reset();
        window_.detach();
        display_.reset();
    }

private:
    // Input, from the window or the script.
    void onButton(int button, bool pressed, double x, double y, int mods);
    void onMove(double x, double y);
    void onScroll(double steps);
    void onKey(int key);

    bool setup();
    void insertBuffers(int width, int height);
    // One render of the active camera into the bound buffers (and the pick buffers when asked).
    bool render(bool withPick);
    void show(bool hud, const std::string& screenshot);
    void buildHud();
    void pick(double x, double y, bool focus);
    void useFreeCamera();
    void cameraChanged() {
        session_.api().markDirty(session_.delegate(), ViewerScene::kCameraPath, OBSCURA_DIRTY_TRANSFORM | OBSCURA_DIRTY_PARAMS);
        changed_ = true;
    }
    void setSetting(const std::string& key, bool on);
    bool playScript();
    void watchFiles();
    const char* activeCamera() const {
        return cameraIndex_ == 0 ? ViewerScene::kCameraPath : sceneCameras_[size_t(cameraIndex_ - 1)].c_str();
    }

    const ViewOptions& o_;
    Session& session_;
    view::ViewerWindow& window_;
    ViewerScene scene_;
    std::unique_ptr<view::DisplayDevice> display_;
    std::unique_ptr<view::DisplaySource> source_;
    std::unique_ptr<view::AovImage> image_;
    std::vector<std::string> sceneCameras_;
    int cameraIndex_ = 0;  // 0: the free camera; i: sceneCameras_[i - 1]
    std::string aov_ = "display";
    std::map<std::string, std::string> buffers_;  // aov -> render buffer path
    int width_ = 0, height_ = 0;
    bool shared_ = false;        // the shown buffer is the plugin's exported memory
    bool exportPending_ = false;  // export again after the next render (new buffer or size)
    bool changed_ = true;
    bool converged_ = false;
    bool hud_ = true;
    bool closing_ = false;
    int accumulated_ = 0;
    double time_ = 0.0;
    std::map<std::string, bool> effects_;
    std::string picked_;
    // Mouse drag state.
    int dragButton_ = -1;
    int dragMods_ = 0;
    double lastX_ = 0, lastY_ = 0, pressX_ = 0, pressY_ = 0;
    bool dragged_ = false;
    // Script playback.
    std::vector<view::ScriptEvent> script_;
    size_t scriptAt_ = 0;
    int framesLeft_ = 0;
    bool waitConverged_ = false;
    std::map<std::string, fs::file_time_type> files_;
    std::chrono::steady_clock::time_point lastWatch_;
    uint64_t semaphoreValue_ = 0;
};

void Viewer::insertBuffers(int width, int height) {
    width_ = width;
    height_ = height;
    scene_.aspect = double(width) / double(height);
    for (const char* aov : {aov_.c_str(), "primId", "instanceId", "depth"}) {
        std::string path = scene_.renderBuffer(aov, width, height);
        if (buffers_.count(aov)) session_.api().markDirty(session_.delegate(), path.c_str(), OBSCURA_DIRTY_PARAMS);
        else session_.api().insertPrim(session_.delegate(), "renderBuffer", path.c_str());
        buffers_[aov] = path;
    }
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
    scene_.camera = view::OrbitCamera(session_.stage().metadata().upAxis);
    const SceneBounds bounds = session_.host().bounds(time_);
    int width = 0, height = 0;
    window_.framebufferSize(width, height);
    scene_.aspect = double(width) / double(height);
    scene_.camera.frame(bounds.centre, bounds.radius, std::min(scene_.verticalFov(), 2 * std::atan(std::tan(0.5 * scene_.verticalFov()) * scene_.aspect)));
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
    for (const char* effect : kEffects) effects_[effect] = std::string(effect) != "dof" && std::string(effect) != "motionBlur";
    effects_["dof"] = effects_["motionBlur"] = true;  // the settings' defaults: on where the camera asks
    insertBuffers(width, height);
    files_ = sceneFiles(session_.stage());
    lastWatch_ = std::chrono::steady_clock::now();
    return true;
}

bool Viewer::render(bool withPick) {
    const ObscuraApiV1& api = session_.api();
    std::vector<ObscuraAovBinding> bindings = {{aov_.c_str(), buffers_[aov_].c_str()}};
    if (withPick)
        for (const char* aov : {"primId", "instanceId", "depth"})
            if (aov_ != aov) bindings.push_back({aov, buffers_[aov].c_str()});
    ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(desc), activeCamera(),
                               {0, 0, width_, height_}, time_, uint32_t(bindings.size()), bindings.data()};
    ObscuraStatus status = api.render(session_.delegate(), &desc);
    if (status != OBSCURA_OK && status != OBSCURA_ERROR_BAD_PRIM_DATA) {
        std::fprintf(stderr, "obscura: render failed: %s\n", session_.lastError().c_str());
        return false;
    }
    accumulated_ = changed_ ? 1 : accumulated_ + 1;
    changed_ = false;
    ObscuraInteropStats interop{};
    converged_ = statsOf(session_, &interop).converged != 0;
    semaphoreValue_ = interop.semaphoreValue;
    if (!display_) {
        view::DisplayDeviceOptions options;
        options.validation = o_.validation;
        options.instanceExtensions = window_.instanceExtensions();
        options.swapchain = true;
        options.deviceName = statsOf(session_).deviceName;
        auto created = view::DisplayDevice::create(options);
        if (auto* problem = std::get_if<std::string>(&created)) {
            std::fprintf(stderr, "obscura: %s\n", problem->c_str());
            return false;
        }
        display_ = std::move(std::get<std::unique_ptr<view::DisplayDevice>>(created));
        window_.attach(*display_);
        image_ = std::make_unique<view::AovImage>(*display_);
    }
    if (exportPending_) {
        exportPending_ = false;
        const ObscuraApiV1_2* interopApi = session_.interopApi();
        ObscuraExternalBuffer exported{};
        exported.sType = OBSCURA_STRUCTURE_TYPE_EXTERNAL_BUFFER;
        exported.structSize = sizeof(exported);
        if (interopApi && display_->canImport() &&
            interopApi->exportRenderBuffer(session_.delegate(), buffers_[aov_].c_str(), &exported) == OBSCURA_OK) {
            auto imported = view::DisplaySource::import(*display_, exported);
            if (auto* problem = std::get_if<std::string>(&imported)) {
                std::fprintf(stderr, "obscura: %s\n", problem->c_str());
                return false;
            }
            source_ = std::move(std::get<std::unique_ptr<view::DisplaySource>>(imported));
            shared_ = true;
            // The exported memory holds frames from the next render on.
            return render(withPick);
        }
        if (o_.display == "shared") {
            std::fprintf(stderr, "obscura: the render buffer cannot be shared: %s\n",
                         interopApi ? session_.lastError().c_str() : "the plugin has no ABI 1.2");
            return false;
        }
        shared_ = false;
    }
    if (!shared_) {
        ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
        if (api.mapRenderBuffer(session_.delegate(), buffers_[aov_].c_str(), &mapped) != OBSCURA_OK) {
            std::fprintf(stderr, "obscura: %s\n", session_.lastError().c_str());
            return false;
        }
        if (!source_ || source_->width() != mapped.width || source_->height() != mapped.height || source_->format() != mapped.format)
            source_ = view::DisplaySource::upload(*display_, mapped.width, mapped.height, mapped.format,
                                                  mapped.rowStride * mapped.height);
        source_->copyFrom(mapped);
        api.unmapRenderBuffer(session_.delegate(), buffers_[aov_].c_str());
    }
    display_->submitAndWait([&](VkCommandBuffer cmd) { image_->record(cmd, *source_, view::aovViewOf(aov_)); },
                            source_->semaphore(), semaphoreValue_);
    return true;
}

void Viewer::useFreeCamera() {
    if (cameraIndex_ == 0) return;
    // The free camera takes over where the scene camera looks from, with its lens.
    const ObscuraSceneDelegate& sd = session_.host().sceneDelegate();
    const char* path = activeCamera();
    double times[1], matrix[16];
    uint32_t count = 0;
    ObscuraValue v{};
    auto number = [&](const char* name, double fallback) {
        if (sd.getValue(sd.userData, path, name, time_, &v) != OBSCURA_OK || !v.data) return fallback;
        return v.type == OBSCURA_VALUE_DOUBLE ? *static_cast<const double*>(v.data) : double(*static_cast<const float*>(v.data));
    };
    scene_.lens.focalLength = number("focalLength", 50.0);
    scene_.lens.horizontalAperture = number("horizontalAperture", 20.955);
    scene_.lens.fStop = number("fStop", 0.0);
    scene_.lens.focusDistance = number("focusDistance", scene_.camera.distance());
    if (sd.getValue(sd.userData, path, "clippingRange", time_, &v) == OBSCURA_OK && v.type == OBSCURA_VALUE_FLOAT2) {
        scene_.lens.nearClip = static_cast<const float*>(v.data)[0];
        scene_.lens.farClip = static_cast<const float*>(v.data)[1];
    }
    if (sd.sampleTransform(sd.userData, path, time_, time_, 1, times, matrix, &count) == OBSCURA_OK && count == 1) {
        view::Matrix4 m;
        std::copy(matrix, matrix + 16, m.begin());
        scene_.camera.lookThrough(m, scene_.lens.focusDistance > 0 ? scene_.lens.focusDistance : scene_.camera.distance());
    }
    cameraIndex_ = 0;
    cameraChanged();
}

void Viewer::onButton(int button, bool pressed, double x, double y, int mods) {
    if (pressed) {
        dragButton_ = button;
        dragMods_ = mods;
        lastX_ = pressX_ = x;
        lastY_ = pressY_ = y;
        dragged_ = false;
        return;
    }
    if (button != dragButton_) return;
    dragButton_ = -1;
    // A click, not a drag: pick what is under the cursor (with ctrl: focus there).
    if (!dragged_ && button == GLFW_MOUSE_BUTTON_LEFT) pick(x, y, (mods & GLFW_MOD_CONTROL) != 0);
}

void Viewer::onMove(double x, double y) {
    if (dragButton_ < 0) return;
    const double dx = x - lastX_, dy = y - lastY_;
    lastX_ = x;
    lastY_ = y;
    if (!dragged_ && std::abs(x - pressX_) + std::abs(y - pressY_) < 3.0) return;
    dragged_ = true;
    useFreeCamera();
    if (dragButton_ == GLFW_MOUSE_BUTTON_MIDDLE || (dragButton_ == GLFW_MOUSE_BUTTON_LEFT && (dragMods_ & GLFW_MOD_SHIFT)))
        scene_.camera.pan(dx, dy, height_, scene_.verticalFov());
    else if (dragButton_ == GLFW_MOUSE_BUTTON_RIGHT)
        scene_.camera.dolly(-dy / 20.0);
    else
        scene_.camera.orbit(dx, dy, width_);
    cameraChanged();
}

void Viewer::onScroll(double steps) {
    useFreeCamera();
    scene_.camera.dolly(steps);
    cameraChanged();
}

void Viewer::onKey(int key) {
    // Fly: a tenth of the distance to the target per press.
    const double step = 0.1 * scene_.camera.distance();
    const std::map<int, view::Vector3> fly = {{GLFW_KEY_W, {0, 0, -1}}, {GLFW_KEY_S, {0, 0, 1}}, {GLFW_KEY_A, {-1, 0, 0}},
                                              {GLFW_KEY_D, {1, 0, 0}},  {GLFW_KEY_E, {0, 1, 0}},  {GLFW_KEY_Q, {0, -1, 0}}};
    if (auto it = fly.find(key); it != fly.end()) {
        useFreeCamera();
        scene_.camera.fly(it->second, step);
        cameraChanged();
    } else if (key == GLFW_KEY_F) {
        useFreeCamera();
        const SceneBounds b = session_.host().bounds(time_);
        scene_.camera.frame(b.centre, b.radius, scene_.verticalFov());
        cameraChanged();
    } else if (key == GLFW_KEY_H) {
        hud_ = !hud_;
    } else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9 && size_t(key - GLFW_KEY_0) <= sceneCameras_.size()) {
        if (key == GLFW_KEY_0) useFreeCamera();
        cameraIndex_ = key - GLFW_KEY_0;
        changed_ = true;
    }
}

void Viewer::pick(double x, double y, bool focus) {
    const int px = int(x), py = int(y);
    if (px < 0 || py < 0 || px >= width_ || py >= height_) return;
    if (!render(true)) return;
    const ObscuraApiV1& api = session_.api();
    auto read = [&](const char* aov) {
        ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
        uint32_t word = 0;
        if (api.mapRenderBuffer(session_.delegate(), buffers_[aov].c_str(), &m) == OBSCURA_OK)
            std::memcpy(&word, static_cast<const char*>(m.data) + size_t(py) * m.rowStride + size_t(px) * 4, 4);
        api.unmapRenderBuffer(session_.delegate(), buffers_[aov].c_str());
        return word;
    };
    const int32_t primId = int32_t(read("primId")), instanceId = int32_t(read("instanceId"));
    const uint32_t depthBits = read("depth");
    float depth = 0;
    std::memcpy(&depth, &depthBits, 4);
    std::string path;
    for (const auto& [prim, type] : session_.host().insertedPrims()) {
        int32_t id = -1;
        if (api.getPrimId(session_.delegate(), prim.c_str(), &id) == OBSCURA_OK && id == primId) path = prim;
    }
    // usdview's picking: an instance names its instancer and its index there.
    std::string instancer = instanceId >= 0 ? session_.host().instancerOf(path) : std::string();
    picked_ = path.empty() ? "nothing" : instancer.empty() ? path : instancer + " instance " + std::to_string(instanceId) + " (" + path + ")";
    std::printf("pick %d %d: %s\n", px, py, picked_.c_str());
    std::fflush(stdout);
    if (focus && !path.empty()) {
        useFreeCamera();
        DepthConversion clip{false, scene_.lens.nearClip, scene_.lens.farClip};
        scene_.lens.focusDistance = linearDepth(depth, clip);
        std::printf("focus distance: %g\n", scene_.lens.focusDistance);
        cameraChanged();
    }
}

void Viewer::setSetting(const std::string& key, bool on) {
    int32_t flag = on ? 1 : 0;
    ObscuraValue value{OBSCURA_VALUE_BOOL, 0, 1, &flag};
    if (session_.api().setRenderSetting(session_.delegate(), key.c_str(), &value) == OBSCURA_OK) {
        effects_[key] = on;
        changed_ = true;
    }
}

void Viewer::buildHud() {
    window_.beginHud();
    if (!hud_) return;
    ImGui::SetNextWindowPos(ImVec2(4, 4), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("Obscura");
    const ObscuraRenderStats stats = statsOf(session_);
    ImGui::Text("%s", stats.deviceName);
    ImGui::Text("%s, %d frame%s %s", shared_ ? "shared image" : "readback", accumulated_, accumulated_ == 1 ? "" : "s",
                converged_ ? "(converged)" : "accumulating");
    uint32_t count = 0;
    session_.api().getPassTimings(session_.delegate(), nullptr, &count);
    std::vector<ObscuraPassTiming> timings(count);
    for (auto& t : timings) t.structSize = sizeof(t);
    session_.api().getPassTimings(session_.delegate(), timings.data(), &count);
    if (ImGui::CollapsingHeader("GPU time per pass", ImGuiTreeNodeFlags_DefaultOpen))
        for (uint32_t i = 0; i < count; ++i) ImGui::Text("%-16s %8.2f ms", timings[i].pass, timings[i].milliseconds);
    if (ImGui::CollapsingHeader("Effects", ImGuiTreeNodeFlags_DefaultOpen))
        for (const char* effect : kEffects) {
            bool on = effects_[effect];
            if (ImGui::Checkbox(effect, &on)) setSetting(effect, on);
        }
    if (ImGui::CollapsingHeader("AOV", ImGuiTreeNodeFlags_DefaultOpen))
        for (const char* aov : kAovs)
            if (ImGui::RadioButton(aov, aov_ == aov) && aov_ != aov) {
                aov_ = aov;
                insertBuffers(width_, height_);
            }
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
        int index = cameraIndex_;
        ImGui::RadioButton("free camera", &index, 0);
        for (size_t i = 0; i < sceneCameras_.size(); ++i) ImGui::RadioButton(sceneCameras_[i].c_str(), &index, int(i + 1));
        if (index != cameraIndex_) onKey(GLFW_KEY_0 + index);
        float focal = float(scene_.lens.focalLength), fStop = float(scene_.lens.fStop),
              focus = float(scene_.lens.focusDistance);
        int blades = scene_.lens.apertureBlades;
        bool lens = ImGui::SliderFloat("focal length (mm)", &focal, 8.0f, 300.0f);
        lens |= ImGui::SliderFloat("f-stop (0: pinhole)", &fStop, 0.0f, 32.0f);
        lens |= ImGui::InputFloat("focus distance", &focus);
        lens |= ImGui::SliderInt("aperture blades", &blades, 0, 12);
        ImGui::TextUnformatted("ctrl+click: focus there");
        if (lens) {
            useFreeCamera();
            scene_.lens.focalLength = focal, scene_.lens.fStop = fStop, scene_.lens.focusDistance = focus;
            scene_.lens.apertureBlades = blades;
            cameraChanged();
        }
    }
    ImGui::Text("pick: %s", picked_.empty() ? "(click)" : picked_.c_str());
    ImGui::End();
}

bool Viewer::playScript() {
    if (framesLeft_ > 0 || (waitConverged_ && !converged_)) return true;
    waitConverged_ = false;
    if (scriptAt_ >= script_.size()) return true;
    const view::ScriptEvent& e = script_[scriptAt_++];
    const std::map<std::string, int> buttons = {{"left", GLFW_MOUSE_BUTTON_LEFT}, {"middle", GLFW_MOUSE_BUTTON_MIDDLE},
                                                {"right", GLFW_MOUSE_BUTTON_RIGHT}};
    const int mods = (e.has("shift") ? GLFW_MOD_SHIFT : 0) | (e.has("ctrl") ? GLFW_MOD_CONTROL : 0);
    auto button = [&] {
        auto it = buttons.find(e.words[0]);
        return it == buttons.end() ? GLFW_MOUSE_BUTTON_LEFT : it->second;
    };
    if (e.verb == "press") onButton(button(), true, e.numbers[0], e.numbers[1], mods);
    else if (e.verb == "release") onButton(button(), false, e.numbers[0], e.numbers[1], mods);
    else if (e.verb == "move") onMove(e.numbers[0], e.numbers[1]);
    else if (e.verb == "click") {
        onButton(GLFW_MOUSE_BUTTON_LEFT, true, e.numbers[0], e.numbers[1], mods);
        onButton(GLFW_MOUSE_BUTTON_LEFT, false, e.numbers[0], e.numbers[1], mods);
    } else if (e.verb == "scroll") onScroll(e.numbers[0]);
    else if (e.verb == "key") {
        const std::string& k = e.words[0];
        int key = k.size() == 1 && std::isalnum(static_cast<unsigned char>(k[0])) ? std::toupper(k[0]) : -1;
        if (key < 0) {
            std::fprintf(stderr, "obscura: script line %d: unknown key '%s'\n", e.line, k.c_str());
            return false;
        }
        onKey(key);
    } else if (e.verb == "aov") {
        if (std::find(std::begin(kAovs), std::end(kAovs), e.words[0]) == std::end(kAovs)) {
            std::fprintf(stderr, "obscura: script line %d: no AOV '%s'\n", e.line, e.words[0].c_str());
            return false;
        }
        aov_ = e.words[0];
        insertBuffers(width_, height_);
    } else if (e.verb == "set") {
        auto eq = e.words[0].find('=');
        std::string value = eq == std::string::npos ? "" : e.words[0].substr(eq + 1);
        setSetting(e.words[0].substr(0, eq), value == "on" || value == "true" || value == "1");
    } else if (e.verb == "lens") {
        useFreeCamera();
        const std::string& name = e.words[0];
        if (name == "focalLength") scene_.lens.focalLength = e.numbers[0];
        else if (name == "fStop") scene_.lens.fStop = e.numbers[0];
        else if (name == "focusDistance") scene_.lens.focusDistance = e.numbers[0];
        else if (name == "apertureBlades") scene_.lens.apertureBlades = int(e.numbers[0]);
        cameraChanged();
    } else if (e.verb == "frames") framesLeft_ = int(e.numbers[0]);
    else if (e.verb == "wait-converged") waitConverged_ = true;
    else if (e.verb == "screenshot") {
        buildHud();
        show(hud_, e.words[0]);
    } else if (e.verb == "close") glfwSetWindowShouldClose(window_.glfw(), GLFW_TRUE);
    return true;
}

void Viewer::show(bool hud, const std::string& screenshot) {
    window_.present(*image_, hud, screenshot);
}

void Viewer::watchFiles() {
    auto now = std::chrono::steady_clock::now();
    if (now - lastWatch_ < std::chrono::milliseconds(500)) return;
    lastWatch_ = now;
    auto files = files_;
    bool modified = false;
    for (auto& [path, time] : files) {
        std::error_code ec;
        auto t = fs::last_write_time(path, ec);
        if (!ec && t != time) modified = true;
    }
    if (!modified) return;
    auto opened = Session::openStage(o_.scene, o_.limits);
    if (auto* error = std::get_if<SessionError>(&opened)) {
        // A file caught half-written, or an edit with a mistake: the scene stays as it was.
        std::fprintf(stderr, "obscura: %s (keeping the scene as it was)\n", error->message.c_str());
        files_ = sceneFiles(session_.stage());
        for (auto& [path, time] : files_) time = fs::last_write_time(path);
        return;
    }
    auto stage = std::move(std::get<std::unique_ptr<usda::Stage>>(opened));
    auto host = std::make_unique<UsdSceneHost>(*stage);
    host->setMessageSink(printHostMessage);
    size_t touched = 0;
    if (host->adoptChanges(session_.host(), session_.api(), session_.delegate(), time_, touched) != OBSCURA_OK) {
        std::fprintf(stderr, "obscura: reload: %s\n", session_.lastError().c_str());
        return;
    }
    scene_.setHost(*host);
    session_.replaceScene(std::move(stage), std::move(host));
    files_ = sceneFiles(session_.stage());
    std::printf("reloaded %s: %zu prim%s changed\n", o_.scene.c_str(), touched, touched == 1 ? "" : "s");
    std::fflush(stdout);
    if (touched) changed_ = true;
}

int Viewer::run() {
    if (!o_.script.empty()) {
        auto read = view::readInputScript(o_.script);
        if (auto* problem = std::get_if<std::string>(&read)) {
            std::fprintf(stderr, "obscura: %s\n", problem->c_str());
            return kExitUsage;
        }
        script_ = std::get<std::vector<view::ScriptEvent>>(read);
    }
    if (!setup()) return kExitPluginOrDevice;
    GLFWwindow* w = window_.glfw();
    glfwSetWindowUserPointer(w, this);
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int mods) {
        if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
        double x = 0, y = 0;
        glfwGetCursorPos(win, &x, &y);
        static_cast<Viewer*>(glfwGetWindowUserPointer(win))->onButton(button, action == GLFW_PRESS, x, y, mods);
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
        static_cast<Viewer*>(glfwGetWindowUserPointer(win))->onMove(x, y);
    });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
        if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
        static_cast<Viewer*>(glfwGetWindowUserPointer(win))->onScroll(dy);
    });
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
        if (action == GLFW_RELEASE || (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard)) return;
        static_cast<Viewer*>(glfwGetWindowUserPointer(win))->onKey(key);
    });
    while (!glfwWindowShouldClose(w)) {
        // Progressive: a frame whenever something changed, then temporal AA accumulates until it
        // has converged; after that the window only waits for input (or the scene's files).
        const bool idle = converged_ && !changed_ && scriptAt_ >= script_.size();
        if (idle) glfwWaitEventsTimeout(0.25);
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
        show(hud_, "");
    }
    return kExitOk;
}

}  // namespace

int runView(const ViewOptions& options) {
    auto window = view::ViewerWindow::open(options.width, options.height, "obscura view " + options.scene);
    if (auto* problem = std::get_if<std::string>(&window)) {
        std::fprintf(stderr, "obscura: %s\n", problem->c_str());
        return kExitPluginOrDevice;
    }
    int exitCode = kExitOk;
    uint32_t viewerErrors = 0;
    {
        auto opened = Session::open(options.scene, options.limits);
        if (auto* error = std::get_if<SessionError>(&opened)) {
            std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
            return error->exitCode;
        }
        Session& session = *std::get<std::unique_ptr<Session>>(opened);
        if (auto problem = session.applySettings(options.settings)) {
            std::fprintf(stderr, "obscura: %s\n", problem->message.c_str());
            return problem->exitCode;
        }
        auto& win = *std::get<std::unique_ptr<view::ViewerWindow>>(window);
        Viewer viewer(options, session, win);
        try {
            exitCode = viewer.run();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "obscura: viewer: %s\n", e.what());
            exitCode = kExitPluginOrDevice;
        }
        viewer.close();
        if (session.loggedErrors() > 0 && exitCode == kExitOk) exitCode = kExitPluginOrDevice;
    }
    viewerErrors = view::DisplayDevice::validationErrors();
    // Closing released every Vulkan object: the validation layer reports any left at vkDestroyDevice.
    if (viewerErrors > 0) {
        std::fprintf(stderr, "obscura: %u Vulkan validation error(s) in the viewer\n", viewerErrors);
        if (exitCode == kExitOk) exitCode = kExitPluginOrDevice;
    }
    return exitCode;
}

}  // namespace obscura::harness
