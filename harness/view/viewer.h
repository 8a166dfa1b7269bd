// obscura view's state and what it does with it. A host of the plugin like the other commands (the
// scene read by the harness, prims inserted through the ABI), with a camera of its own, a window
// that shows the render buffers without reading them back where the plugin exports them (ABI
// 1.2), a HUD, picking and reloading of the scene's files when they change on disk. Each concern
// has a file of its own: viewer.cpp (setup, the loop, rendering and showing), viewer_input.cpp
// (mouse and keys), viewer_hud.cpp, viewer_pick.cpp, script_playback.cpp, scene_reload.cpp.
#pragma once

#include "harness/commands.h"
#include "harness/session.h"
#include "harness/view/display_device.h"
#include "harness/view/input_script.h"
#include "harness/view/scene_reload.h"
#include "harness/view/viewer_scene.h"
#include "harness/view/viewer_window.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace obscura::harness::view {

// The AOVs picking reads.
inline constexpr const char* kPickAovs[] = {"primId", "instanceId", "depth"};
// Effects the HUD and the keys toggle (render settings, named as in `obscura info`).
inline constexpr const char* kEffects[] = {"taa", "ssao", "shadows", "dof", "motionBlur"};
// The AOVs the window shows.
inline constexpr const char* kAovs[] = {"display", "depth", "normal", "motion", "primId"};

class Viewer {
public:
    Viewer(const ViewOptions& options, Session& session, ViewerWindow& window)
        : o_(options), session_(session), window_(window), scene_(session.host()) {}

    // Runs until the window closes; returns the exit code.
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
    // viewer.cpp
    bool setup();
    void insertBuffers(int width, int height);
    // One render of the active camera into the bound buffers (and the pick buffers when asked),
    // shown in the display image.
    bool render(bool withPick);
    bool createDisplay();
    // The shown buffer's source: the plugin's exported memory where it can be shared, else a copy.
    bool updateSource(bool& exportedNow);
    void watchFiles();
    void cameraChanged() {
        session_.api().markDirty(session_.delegate(), ViewerScene::kCameraPath,
                                 OBSCURA_DIRTY_TRANSFORM | OBSCURA_DIRTY_PARAMS);
        changed_ = true;
    }
    const char* activeCamera() const {
        return cameraIndex_ == 0 ? ViewerScene::kCameraPath : sceneCameras_[size_t(cameraIndex_ - 1)].c_str();
    }

    // viewer_input.cpp: the window's mouse and keys, and the script's.
    void listen();
    void onButton(int button, bool pressed, double x, double y, int mods);
    void onMove(double x, double y);
    void onScroll(double steps);
    void onKey(int key);
    void useFreeCamera();
    void setSetting(const std::string& key, bool on);
    void showAov(const std::string& aov);

    // viewer_hud.cpp
    void buildHud();
    // viewer_pick.cpp
    void pick(double x, double y, bool focus);
    // script_playback.cpp: the next event of the script, unless a wait holds; false on a bad event.
    bool playScript();

    const ViewOptions& o_;
    Session& session_;
    ViewerWindow& window_;
    ViewerScene scene_;
    std::unique_ptr<DisplayDevice> display_;
    std::unique_ptr<DisplaySource> source_;
    std::unique_ptr<AovImage> image_;
    std::vector<std::string> sceneCameras_;
    int cameraIndex_ = 0;  // 0: the free camera; i: sceneCameras_[i - 1]
    std::string aov_ = "display";
    // Render buffer paths: the shown AOV's ("shown", which may be the plugin's exported memory) and
    // picking's (by AOV name), apart so that picking can map its buffers whatever is shown.
    std::map<std::string, std::string> buffers_;
    int width_ = 0, height_ = 0;
    bool exportPending_ = false;  // export again after the next render (new buffer or size)
    bool changed_ = true;
    bool converged_ = false;
    bool hud_ = true;
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
    std::vector<ScriptEvent> script_;
    size_t scriptAt_ = 0;
    int framesLeft_ = 0;
    bool waitConverged_ = false;
    bool waitReload_ = false;
    // Reloading.
    std::optional<SceneReload> reload_;
    bool reportSync_ = false;  // print how many prims the render after a reload synced
};

}  // namespace obscura::harness::view
