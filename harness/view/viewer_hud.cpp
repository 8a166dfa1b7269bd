// The viewer's HUD (Dear ImGui): the device, the display path, frames accumulated and whether they
// converged, the GPU time of each pass, the effects, the shown AOV, the cameras and the lens.
#include "harness/view/viewer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

namespace obscura::harness::view {

void Viewer::buildHud() {
    window_.beginHud();
    if (!hud_) return;
    ImGui::SetNextWindowPos(ImVec2(4, 4), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("Obscura");
    ImGui::Text("%s", session_.deviceName().c_str());
    const bool shared = source_ && source_->shared();
    ImGui::Text("%s, %d frame%s %s", shared ? "shared image" : "readback", accumulated_, accumulated_ == 1 ? "" : "s",
                converged_ ? "(converged)" : "accumulating");
    if (ImGui::CollapsingHeader("GPU time per pass", ImGuiTreeNodeFlags_DefaultOpen))
        for (const ObscuraPassTiming& timing : session_.passTimings())
            ImGui::Text("%-16s %8.2f ms", timing.pass, timing.milliseconds);
    if (ImGui::CollapsingHeader("Effects", ImGuiTreeNodeFlags_DefaultOpen))
        for (const char* effect : kEffects) {
            bool on = effects_[effect];
            if (ImGui::Checkbox(effect, &on)) setSetting(effect, on);
        }
    if (ImGui::CollapsingHeader("AOV", ImGuiTreeNodeFlags_DefaultOpen))
        for (const char* aov : kAovs)
            if (ImGui::RadioButton(aov, aov_ == aov) && aov_ != aov) showAov(aov);
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

}  // namespace obscura::harness::view
