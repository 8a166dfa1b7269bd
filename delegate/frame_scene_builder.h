// Packs the synced prims into the per-frame GPU records the passes read (camera constants,
// instances, materials, lights) and the list of draws.
#pragma once

#include "delegate/prims/camera.h"
#include "delegate/prims/light.h"
#include "delegate/prims/prim.h"
#include "delegate/purposes.h"
#include "delegate/shadow_views.h"
#include "delegate/texture_cache.h"
#include "passes/frame_scene.h"
#include "renderer/frame_renderer.h"

#include <array>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <vector>

namespace obscura::delegate {

using renderer::FrameSample;
using renderer::FrameView;
using renderer::InstanceModels;

// The prims and settings a frame is built from, seen from one viewpoint.
struct FrameSceneInputs : renderer::FrameViewpoint {
    const std::map<std::string, std::unique_ptr<Prim>>& prims;
    const Camera& camera;
    uint32_t width;
    uint32_t height;
    double exposureStops;  // render setting, added to the camera's exposure
    TextureCache& textures;
    const ShadowSettings& shadows;
    // The dome that lights through its texture (environmentDome()), or null.
    const Light* environmentDome;
    // Render setting domeLightCameraVisibility (Hydra's): visible domes are the background the
    // camera sees where nothing is drawn, and it is opaque.
    bool domeBackdrop = true;
    // Render setting pixelAspectRatio (UsdRenderSettingsBase's): a pixel's width over its height;
    // the image the camera's aperture is conformed to is width x pixelAspectRatio wide.
    double pixelAspectRatio = 1.0;
    // Render setting includedPurposes (purposes.h): the purposes drawn; prims of others are not.
    uint32_t includedPurposes = kPurposeDefault | kPurposeRender;
};

// The first visible dome with a texture, in path order: the one the environment maps are made
// from. Further textured domes go to `ignored` (they light with their constant colour).
const Light* environmentDome(const std::map<std::string, std::unique_ptr<Prim>>& prims,
                             std::vector<std::string>& ignored);

// What the frame could not honour, for the delegate to report.
struct FrameSceneShortfalls {
    uint32_t lightsWithoutShadowRoom = 0;  // shadow-casting lights the atlas had no room for
    std::vector<std::string> unclippedLights;  // lights whose clip volume could not be used, and why
    std::vector<std::string> unresolvedSubsetMaterials;  // material subsets bound to no material
};

// The unjittered view the frame sees through: the camera's, or the reference sub-frame's.
FrameView frameView(const FrameSceneInputs& inputs);

passes::FrameScene buildFrameScene(gpu::Device& device, const FrameSceneInputs& inputs, FrameSceneShortfalls& shortfalls);

}  // namespace obscura::delegate
