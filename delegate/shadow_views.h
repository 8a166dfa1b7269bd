// The frame's shadow atlas on the CPU: which lights cast shadows, the views each needs (cascades
// of a distant light, cube faces of a sphere light), where each view's tile lies in the atlas,
// which draws reach it, and the records the lighting pass reads.
#pragma once

#include "delegate/bounds.h"
#include "delegate/shadow_cascades.h"
#include "passes/frame_scene.h"

#include <vector>

namespace obscura::delegate {

struct ShadowSettings {
    bool enabled = true;          // render setting `shadows`
    uint32_t resolution = 1024;   // `shadows:resolution`: side of one view's tile in texels
    uint32_t cascades = 4;        // `shadows:cascades`: cascades per distant light
};

// The atlas holds at most this many texels on a side (a 256 MiB depth image); lights whose
// views no longer fit cast no shadow.
constexpr uint32_t kMaxShadowAtlasSide = 8192;

struct ShadowAtlasBuild {
    passes::ShadowAtlas atlas;                     // all but its GPU records
    std::vector<passes::ShadowViewData> records;   // one per view, for atlas.records
    std::vector<Matrix4d> viewProjections;          // one per view: world -> clip, in double precision
    uint32_t lightsLeftUnshadowed = 0;  // lights that cast shadows but found no room in the atlas
};

struct ShadowInputs {
    const ShadowSettings& settings;
    const ShadowedCamera& camera;
    double cameraNear;  // the camera's clipping range (view distances)
    double cameraFar;
    const std::vector<Aabb>& drawBounds;  // world bounds of each FrameScene draw, all instances
};

// Fills the shadow field of each light in `lights` whose castsShadows entry is true and
// returns the atlas with its views and records. CPU only.
ShadowAtlasBuild buildShadowAtlas(const ShadowInputs& inputs, std::vector<passes::LightData>& lights,
                                  const std::vector<bool>& castsShadows);

}  // namespace obscura::delegate
