// DistantLight, SphereLight, RectLight, DiskLight, CylinderLight and DomeLight sprims (UsdLux). Radiometric
// conventions (docs/ARCHITECTURE.md): inputs:intensity * 2^inputs:exposure * inputs:color is the
// emitted radiance; a distant light's irradiance at normal incidence is that radiance times the
// solid angle of its disc (2 pi (1 - cos(angle / 2))), or the intensity itself when
// inputs:normalize is on; normalized sphere, rectangle, disk and cylinder lights divide their
// radiance by their surface area; rectangles and disks emit from their front (-Z) face only,
// cylinders (along local X) from their side, not their caps; a dome is
// constant radiance all around, or its latlong texture's texels times that scale (the texture
// oriented by the transform). ShapingAPI's cone, softness and focus shape the local lights.
#pragma once

#include "delegate/prims/prim.h"
#include "delegate/texture_cache.h"
#include "passes/frame_data.h"

namespace obscura::delegate {

class Light final : public Prim {
public:
    Light(std::string path, const schema::PrimSchema& schema, passes::LightType type)
        : Prim(std::move(path), schema), type_(type) {}
    bool visible() const { return visible_; }
    bool castsShadows() const { return castsShadows_; }  // inputs:shadow:enable (UsdLuxShadowAPI)
    // obscura:clipVolume: the mesh the light is clipped to (passes/clip_volumes.h), if any.
    const std::optional<std::string>& clipVolume() const { return clipVolume_; }
    const passes::LightData& data() const { return data_; }
    // The light placed by its transform at an absolute time within the camera's shutter (between
    // the samples synced over it): reference sub-frames and the motion-blurred frame's centre.
    passes::LightData dataAt(double time) const;
    const std::string& warning() const { return warning_; }
    // A dome's latlong radiance texture; null for a constant dome (no file, a file that cannot be
    // read, or a layout other than latlong).
    const TexturePtr& environment() const { return environment_; }
    const Matrix4d& transform() const { return transform_; }

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    // What the light's inputs say, before its transform places it.
    struct Shape {
        std::array<double, 3> radiance{};  // intensity x 2^exposure x colour (x colour temperature)
        bool normalize = false;
        double angle = 0.0;                // distant: radians
        double halfX = 0.0, halfY = 0.0;   // sphere: radius in halfX; rect: half width, height; disk: radius
        std::array<float, 4> factors{};    // LightData::factors before the frame's
        std::array<float, 4> shaping{};    // LightData::shaping
    };
    passes::LightData placed(const Matrix4d& transform) const;
    passes::LightType type_;
    Shape shape_;
    Matrix4d transform_ = kIdentity;
    std::vector<TransformSample> shutterTransforms_;  // over the shutter: reference sub-frames, motion blur
    passes::LightData data_{};
    TexturePtr environment_;
    bool visible_ = true;
    bool castsShadows_ = true;
    std::optional<std::string> clipVolume_;
    std::string warning_;
};

// The light with its influence range (LightData::factors.w) set for a frame exposed by
// `exposureScale`: the distance tiled culling bounds it by.
passes::LightData withInfluenceRange(passes::LightData light, double exposureScale);

// The largest irradiance the light gives anywhere, before exposure: a distant light's at normal
// incidence, pi L at a dome's or a local light's own surface (the brightest channel).
double brightestIrradiance(const passes::LightData& light);

// The reference mode's stand-in for `light` in one sub-frame (docs/ARCHITECTURE.md "Reference
// mode"): one point of its emitter, picked by `u` in [0, 1)^2, lighting and shadowing like a point
// (hard shadow maps), so that the mean over stratified sub-frames converges to the integral over
// the emitter of its visible, cosine-weighted radiance, penumbrae included (the accumulation
// buffer's soft shadows, Haeberli & Akeley 1990). A distant light: a direction within its cone,
// uniform in solid angle (concentric disc mapping), with the light's irradiance and no angle.
// Every other light is returned as it is.
passes::LightData emitterSample(const passes::LightData& light, std::array<double, 2> u);

// Linear Rec.709 colour of a black body at `kelvin`, scaled to luminance 1 (UsdLux
// colorTemperature: the light's colour is multiplied by it).
std::array<float, 3> blackbodyColor(double kelvin);

}  // namespace obscura::delegate
