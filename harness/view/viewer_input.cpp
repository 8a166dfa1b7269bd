// The viewer's mouse and keys (from the window, or played from a script): orbit, pan, dolly and fly
// the free camera, pick, switch cameras, effects and the shown AOV.
#include "harness/view/viewer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cmath>

namespace obscura::harness::view {
namespace {

Viewer& viewerOf(GLFWwindow* window) { return *static_cast<Viewer*>(glfwGetWindowUserPointer(window)); }

// Input the HUD takes is not the viewport's.
bool hudWants(bool mouse) {
    return ImGui::GetCurrentContext() && (mouse ? ImGui::GetIO().WantCaptureMouse : ImGui::GetIO().WantCaptureKeyboard);
}

}  // namespace

void Viewer::listen() {
    GLFWwindow* w = window_.glfw();
    glfwSetWindowUserPointer(w, this);
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int mods) {
        if (hudWants(true)) return;
        double x = 0, y = 0;
        glfwGetCursorPos(win, &x, &y);
        viewerOf(win).onButton(button, action == GLFW_PRESS, x, y, mods);
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) { viewerOf(win).onMove(x, y); });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
        if (!hudWants(true)) viewerOf(win).onScroll(dy);
    });
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
        if (action != GLFW_RELEASE && !hudWants(false)) viewerOf(win).onKey(key);
    });
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
    const std::map<int, Vector3> fly = {{GLFW_KEY_W, {0, 0, -1}}, {GLFW_KEY_S, {0, 0, 1}}, {GLFW_KEY_A, {-1, 0, 0}},
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
        Matrix4 m;
        std::copy(matrix, matrix + 16, m.begin());
        scene_.camera.lookThrough(m, scene_.lens.focusDistance > 0 ? scene_.lens.focusDistance : scene_.camera.distance());
    }
    cameraIndex_ = 0;
    cameraChanged();
}

void Viewer::setSetting(const std::string& key, bool on) {
    int32_t flag = on ? 1 : 0;
    ObscuraValue value{OBSCURA_VALUE_BOOL, 0, 1, &flag};
    if (session_.api().setRenderSetting(session_.delegate(), key.c_str(), &value) == OBSCURA_OK) {
        effects_[key] = on;
        changed_ = true;
    }
}

void Viewer::showAov(const std::string& aov) {
    aov_ = aov;
    insertBuffers(width_, height_);
}

}  // namespace obscura::harness::view
