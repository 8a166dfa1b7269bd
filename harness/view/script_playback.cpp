// A script of input events played into the viewer (input_script.h): the same handlers as the
// window's mouse and keys, one event per frame of the loop, held while a wait is pending.
#include "harness/view/viewer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace obscura::harness::view {

bool Viewer::playScript() {
    if (framesLeft_ > 0 || (waitConverged_ && !converged_) || waitReload_) return true;
    waitConverged_ = false;
    if (scriptAt_ >= script_.size()) return true;
    const ScriptEvent& e = script_[scriptAt_++];
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
        showAov(e.words[0]);
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
    else if (e.verb == "wait-reload") waitReload_ = true;
    else if (e.verb == "screenshot") {
        buildHud();
        window_.present(*image_, hud_, e.words[0]);
    } else if (e.verb == "close") glfwSetWindowShouldClose(window_.glfw(), GLFW_TRUE);
    return true;
}

}  // namespace obscura::harness::view
