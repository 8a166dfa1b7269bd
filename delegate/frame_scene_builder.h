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

#include <array>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace obscura::delegate {

// Where on the lens, when in the shutter and where within the pixel a reference sub-frame looks
// from (Camera::viewMatrix / projectionMatrix with a lens offset), and which point of each light's
// emitter lights it.
struct FrameSample {
    double time;                        // absolute time code, within the camera's shutter
    std::array<double, 2> lensOffset;   // camera space, scene units
    std::array<double, 2> pixelJitter;  // pixels
    std::array<double, 2> emitter;      // [0, 1)^2: where on each light's emitter (emitterSample)
};

// Temporal AA's object motion: every drawn instance's model by a key stable from frame to frame
// (instanceKey()), as the last frame drew it and as this one does.
using InstanceModels = std::unordered_map<uint64_t, Matrix4d>;

struct FrameSceneInputs {
    const std::map<std::string, std::unique_ptr<Prim>>& prims;
    const Camera& camera;
    uint32_t width;
    uint32_t height;
    double exposureStops;  // render setting, added to the camera's exposure
    TextureCache& textures;
    const ShadowSettings& shadows;
    // The dome that lights through its texture (environmentDome()), or null.
    const Light* environmentDome;
    std::optional<FrameSample> sample = std::nullopt;  // none: the pinhole camera at the frame's time
    // Temporal AA's sub-pixel shift, applied after the projection frameView() gives for everything
    // that rasterises or reads the G-buffer (CameraData); frameView() and the shadow cascades
    // keep the unjittered frustum, so SSAO's history check and the cascades' texel grids do not
    // move with the jitter. Identity for reference sub-frames, which jitter through `sample`.
    Matrix4d clipJitter = kIdentity;
    // Temporal AA's place in its jitter cycle (CameraData::noiseFrame): the shadow filter's turn.
    uint32_t noiseFrame = 0;
    // Hybrid AA (seed 004, render setting taa:hybridDistance in scene units): instances whose world
    // bounds come nearer the eye than this are drawn without the jitter and edge-anti-aliased
    // (kInstanceEdgeAa); the rest are temporally anti-aliased. 0: every instance is temporal.
    double edgeAaDistance = 0.0;
    // Render setting domeLightCameraVisibility (Hydra's): visible domes are the background the
    // camera sees where nothing is drawn, and it is opaque.
    bool domeBackdrop = true;
    // Render setting pixelAspectRatio (UsdRenderSettingsBase's): a pixel's width over its height;
    // the image the camera's aperture is conformed to is width x pixelAspectRatio wide.
    double pixelAspectRatio = 1.0;
    // Render setting includedPurposes (purposes.h): the purposes drawn; prims of others are not.
    uint32_t includedPurposes = kPurposeDefault | kPurposeRender;
    // The camera's shutter, absolute time codes [open, close], when the frame samples it: a
    // motion-blurred frame (no `sample`) is seen at its centre (the reconstruction filter spreads
    // each pixel both ways along its velocity, McGuire et al. 2012) and the passes get where the
    // camera and every instance are at its ends; a reference sub-frame (`sample`) is seen at its
    // own time within it. None: the shutter is closed or not sampled (motionBlur off), the frame is
    // seen at the sync time.
    std::optional<std::array<double, 2>> shutter = std::nullopt;
    // The part of `shutter` a motion-blurred frame (no `sample`) covers, as fractions of it
    // [start, end]: the whole of it in a real-time frame; one stratum in a sample of a still's
    // accumulation (TemporalAaStep::shutterStratum). The frame is seen at the part's middle and its
    // velocities span the part alone.
    std::array<double, 2> shutterSpan{0.0, 1.0};
    // Where on the aperture a still's accumulated frame (no `sample`) looks from
    // (TemporalAaStep::lensStratum): camera space x right, y up, scene units, the focus plane kept
    // in place (Camera::projectionMatrix with a lens offset). Zero: the lens's centre.
    std::array<double, 2> lensOffset{0.0, 0.0};
    // A sample of a still's mean: MSAA samples resolve linearly (CameraData::linearResolve).
    bool linearResolve = false;
    // Temporal AA: the last frame's models (instances whose model differs get an
    // InstanceReprojection record), and where this frame's go; null without temporal AA.
    const InstanceModels* lastModels = nullptr;
    InstanceModels* models = nullptr;
};

// The first visible dome with a texture, in path order: the one the environment maps are made
// from. Further textured domes go to `ignored` (they light with their constant colour).
const Light* environmentDome(const std::map<std::string, std::unique_ptr<Prim>>& prims,
                             std::vector<std::string>& ignored);

// What the frame could not honour, for the delegate to report.
struct FrameSceneShortfalls {
    uint32_t lightsWithoutShadowRoom = 0;  // shadow-casting lights the atlas had no room for
    std::vector<std::string> unclippedLights;  // lights whose clip volume could not be used, and why
};

// World-to-view and view-to-clip (row-vector convention) the frame sees through: the camera's, or
// the reference sub-frame's.
struct FrameView {
    Matrix4d view;
    Matrix4d projection;
};
FrameView frameView(const FrameSceneInputs& inputs);

passes::FrameScene buildFrameScene(gpu::Device& device, const FrameSceneInputs& inputs, FrameSceneShortfalls& shortfalls);

}  // namespace obscura::delegate
