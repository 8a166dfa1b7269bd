// The camera sprim: UsdGeomCamera's projection, clipping and (stored for the camera passes)
// lens and shutter parameters.
#pragma once

#include "delegate/prims/prim.h"

namespace obscura::delegate {

struct CameraParams {
    Matrix4d cameraToWorld = kIdentity;
    bool orthographic = false;
    double focalLength = 50.0;              // tenths of a scene unit
    double horizontalAperture = 20.955;
    double verticalAperture = 15.2908;
    double horizontalApertureOffset = 0.0;
    double verticalApertureOffset = 0.0;
    std::array<float, 2> clippingRange{1.0f, 1000000.0f};
    double fStop = 0.0;
    double focusDistance = 0.0;
    double shutterOpen = 0.0;
    double shutterClose = 0.0;
    double exposure = 0.0;
    double exposureTime = 1.0;       // physical exposure (UsdGeomCamera exposure:*)
    double exposureIso = 100.0;
    double exposureFStop = 1.0;
    double exposureResponsivity = 1.0;
    int32_t apertureBlades = 0;
    double apertureRotation = 0.0;
};

class Camera final : public Prim {
public:
    using Prim::Prim;
    const CameraParams& params() const { return params_; }

    // World-to-view and view-to-clip (Vulkan clip space: y down, depth 0 at near, 1 at far), in
    // the row-vector convention. The aperture is conformed to the image aspect by "fit" (the
    // whole authored aperture stays visible, as usdview's default).
    Matrix4d viewMatrix() const;
    Matrix4d projectionMatrix(double imageAspect) const;

    // UsdGeomCamera's linear exposure scale: time x ISO x 2^exposure x responsivity /
    // (100 x fStop^2) (the photographic exposure H ~ t S / N^2, normalised to 1 at the defaults).
    double linearExposureScale() const;

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    CameraParams params_;
};

}  // namespace obscura::delegate
