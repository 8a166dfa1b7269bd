// UsdRender's RenderSettings, RenderProduct and RenderVar prims as usdrecord and husk honour
// them: what to render (the camera, the resolution, the pixel aspect ratio, the purposes drawn)
// and what to write (the product's file name and the AOVs of its ordered vars). Schema:
// https://openusd.org/release/api/usd_render_page_front.html
#pragma once

#include "harness/usd_scene_host.h"
#include "harness/usda/stage.h"

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace obscura::harness {

// What a RenderSettings prim and one of its RenderProducts ask for (aspectRatioConformPolicy other
// than expandAperture, Obscura's only one, and dataWindowNDC other than the whole image are
// reported and not honoured); unset fields are not authored
// (the product's own opinions win over the settings', as UsdRenderProduct inherits
// UsdRenderSettingsBase).
struct StageRenderSettings {
    std::string path;                               // the RenderSettings prim
    std::string camera;                             // "" when the camera relationship is not usable
    std::optional<std::array<int, 2>> resolution;   // pixels
    std::optional<double> pixelAspectRatio;
    std::optional<std::string> includedPurposes;    // comma-separated, as the render setting of the name
    std::optional<bool> disableMotionBlur;          // the render setting motionBlur off
    std::optional<bool> disableDepthOfField;        // the render setting dof off
    std::string productName;                        // the product's file name, "" when none
    std::vector<std::string> aovs;                  // Obscura's AOV names, from the product's orderedVars
};

// The RenderSettings prim `path` (from --render-settings or the stage's renderSettingsPrimPath) as
// one StageRenderSettings per product, in the order of its `products` (one without a product name
// when it has none), or why it cannot be used (no such prim, not a RenderSettings prim). Bad
// values on it, its products or their vars (wrong types, missing relationship targets, RenderVars
// no AOV answers) are reported in `messages` with the prim and where it is authored, and left out.
std::variant<std::vector<StageRenderSettings>, std::string> readStageRenderSettings(const usda::Stage& stage,
                                                                                    const std::string& path,
                                                                                    std::vector<HostMessage>& messages);

}  // namespace obscura::harness
