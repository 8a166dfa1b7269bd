// The camera sprim: UsdGeomCamera's projection, clipping and (stored for the camera passes)
// lens and shutter parameters.
#pragma once

#include "delegate/prims/prim.h"
#include "pass_support/thin_lens.h"

namespace obscura::delegate {

// Until the first sync, a camera has the schema's defaults (schemas/camera.json).
struct CameraParams {
    Matrix4d cameraToWorld = kIdentity;
    bool orthographic;
    double focalLength;  // tenths of a scene unit
    double horizontalAperture;
    double verticalAperture;
    double horizontalApertureOffset;
    double verticalApertureOffset;
    std::array<float, 2> clippingRange;
    double fStop;
    double focusDistance;
    double shutterOpen;
    double shutterClose;
    double exposure;
    double exposureTime;  // physical exposure (UsdGeomCamera exposure:*)
    double exposureIso;
    double exposureFStop;
    double exposureResponsivity;
    int32_t apertureBlades;
    double apertureRotation;
};

class Camera final : public Prim {
public:
    Camera(std::string path, const schema::PrimSchema& schema);
    const CameraParams& params() const { return params_; }
    // Why the camera's lens has no depth of field although its fStop asks for it; empty otherwise.
    const std::string& warning() const { return warning_; }

    // World-to-view and view-to-clip (Vulkan clip space: y down, depth 0 at near, 1 at far), in
    // the row-vector convention. The aperture is conformed to the image aspect by "fit" (the
    // whole authored aperture stays visible, as usdview's default).
    Matrix4d viewMatrix() const;
    Matrix4d projectionMatrix(double imageAspect) const;

    // UsdGeomCamera's linear exposure scale: time x ISO x 2^exposure x responsivity /
    // (100 x fStop^2) (the photographic exposure H ~ t S / N^2, normalised to 1 at the defaults).
    double linearExposureScale() const;

    // The lens for depth of field (pass_support/thin_lens.h): scene units, the film gate conformed to the
    // image aspect. Orthographic cameras have no lens (fStop 0).
    passes::ThinLens thinLens(double imageAspect) const;
    passes::ApertureShape apertureShape() const;

    // A reference sub-frame's view: the eye moved by `lensOffset` (camera space x right, y up, scene
    // units) on the aperture at absolute `time` within the shutter. The projection shears so the
    // focus plane keeps its image (an accumulation-buffer camera), and `ndcJitter` shifts the image.
    Matrix4d cameraToWorldAt(double time) const;
    Matrix4d viewMatrix(std::array<double, 2> lensOffset, double time) const;
    Matrix4d projectionMatrix(double imageAspect, std::array<double, 2> lensOffset, std::array<double, 2> ndcJitter) const;

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    // The lens, clipping, exposure and shutter as the host authored them (schema defaults elsewhere).
    static CameraParams readParams(SceneAccess& s);
    CameraParams params_;
    std::vector<TransformSample> shutterTransforms_;
    std::string warning_;
};

}  // namespace obscura::delegate
