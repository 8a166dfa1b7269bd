#include "delegate/prims/camera.h"

#include <cmath>

namespace obscura::delegate {

void Camera::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext&) {
    if (bits & OBSCURA_DIRTY_TRANSFORM) {
        auto samples = s.sampleTransform(s.time(), s.time());
        params_.cameraToWorld = samples.front().matrix;
    }
    if (bits & OBSCURA_DIRTY_PARAMS) {
        CameraParams& p = params_;
        p.orthographic = s.getToken("projection") == "orthographic";
        p.focalLength = s.getDouble("focalLength");
        p.horizontalAperture = s.getDouble("horizontalAperture");
        p.verticalAperture = s.getDouble("verticalAperture");
        p.horizontalApertureOffset = s.getDouble("horizontalApertureOffset");
        p.verticalApertureOffset = s.getDouble("verticalApertureOffset");
        p.clippingRange = s.getFloat2("clippingRange");
        p.fStop = s.getDouble("fStop");
        p.focusDistance = s.getDouble("focusDistance");
        p.shutterOpen = s.getDouble("shutter:open");
        p.shutterClose = s.getDouble("shutter:close");
        p.exposure = s.getDouble("exposure");
        p.exposureTime = s.getDouble("exposure:time");
        p.exposureIso = s.getDouble("exposure:iso");
        p.exposureFStop = s.getDouble("exposure:fStop");
        p.exposureResponsivity = s.getDouble("exposure:responsivity");
        p.apertureBlades = s.getInt("obscura:apertureBlades");
        p.apertureRotation = s.getDouble("obscura:apertureRotation");
        if (p.focalLength <= 0 || p.horizontalAperture <= 0 || p.verticalAperture <= 0)
            throw PrimDataError(s.path() + ": focalLength and apertures must be positive");
        if (!(p.clippingRange[0] > 0 && p.clippingRange[1] > p.clippingRange[0]))
            throw PrimDataError(s.path() + ": clippingRange must satisfy 0 < near < far");
        if (!(p.exposureFStop > 0) || p.exposureTime < 0 || p.exposureIso < 0 || p.exposureResponsivity < 0)
            throw PrimDataError(s.path() + ": exposure:fStop must be positive and exposure:time, exposure:iso, "
                                           "exposure:responsivity not negative");
    }
}

double Camera::linearExposureScale() const {
    const CameraParams& p = params_;
    return p.exposureTime * p.exposureIso * std::exp2(p.exposure) * p.exposureResponsivity /
           (100.0 * p.exposureFStop * p.exposureFStop);
}

Matrix4d Camera::viewMatrix() const {
    Matrix4d view = kIdentity;
    if (!invert(params_.cameraToWorld, view)) return kIdentity;
    return view;
}

Matrix4d Camera::projectionMatrix(double imageAspect) const {
    const CameraParams& p = params_;
    double ha = p.horizontalAperture, va = p.verticalAperture;
    // Conform window policy "fit": widen whichever aperture the image aspect needs.
    if (imageAspect > ha / va) ha = va * imageAspect;
    else va = ha / imageAspect;
    double n = p.clippingRange[0], f = p.clippingRange[1];
    // Column-vector form first (rows below), transposed at the end for the row-vector convention.
    Matrix4d c{};
    if (!p.orthographic) {
        c[0] = 2.0 * p.focalLength / ha;
        c[2] = 2.0 * p.horizontalApertureOffset / ha;
        c[5] = -2.0 * p.focalLength / va;  // Vulkan's y points down
        c[6] = -2.0 * p.verticalApertureOffset / va;
        c[10] = f / (n - f);
        c[11] = n * f / (n - f);
        c[14] = -1.0;
    } else {
        // Orthographic apertures are in tenths of a scene unit too.
        double w = ha / 10.0, h = va / 10.0;
        c[0] = 2.0 / w;
        c[3] = -2.0 * (p.horizontalApertureOffset / 10.0) / w;
        c[5] = -2.0 / h;
        c[7] = 2.0 * (p.verticalApertureOffset / 10.0) / h;
        c[10] = -1.0 / (f - n);
        c[11] = -n / (f - n);
        c[15] = 1.0;
    }
    return transpose(c);
}

}  // namespace obscura::delegate
