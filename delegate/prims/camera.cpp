#include "delegate/prims/camera.h"

#include "schemas/camera_depth.h"

#include <algorithm>
#include <cmath>

namespace obscura::delegate {

Camera::Camera(std::string path, const schema::PrimSchema& schema) : Prim(std::move(path), schema) {
    // A host that authors nothing: every value is the schema's default.
    const ObscuraSceneDelegate none{OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE, nullptr, sizeof(none)};
    SceneAccess defaults(none, schema, this->path(), 0.0);
    params_ = readParams(defaults);
}

CameraParams Camera::readParams(SceneAccess& s) {
    CameraParams p;
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
    return p;
}

void Camera::pull(SceneAccess& s, ObscuraDirtyBits, SyncContext&) {
    if (s.anyDirtyBut({"transform"})) {
        CameraParams p = readParams(s);
        p.cameraToWorld = params_.cameraToWorld;
        if (p.focalLength <= 0 || p.horizontalAperture <= 0 || p.verticalAperture <= 0)
            throw PrimDataError(s.path() + ": focalLength and apertures must be positive");
        if (!(p.clippingRange[0] > 0 && p.clippingRange[1] > p.clippingRange[0]))
            throw PrimDataError(s.path() + ": clippingRange must satisfy 0 < near < far");
        if (!(p.exposureFStop > 0) || p.exposureTime < 0 || p.exposureIso < 0 || p.exposureResponsivity < 0)
            throw PrimDataError(s.path() + ": exposure:fStop must be positive and exposure:time, exposure:iso, "
                                           "exposure:responsivity not negative");
        if (p.fStop < 0 || p.focusDistance < 0)
            throw PrimDataError(s.path() + ": fStop and focusDistance must not be negative");
        if (p.apertureBlades < 0 || p.apertureBlades == 1 || p.apertureBlades == 2)
            throw PrimDataError(s.path() + ": obscura:apertureBlades must be 0 (round) or at least 3");
        // USD's default focusDistance is 0: a file that sets only fStop gets no depth of field.
        warning_.clear();
        if (p.fStop > 0 && !p.orthographic && p.focusDistance <= p.focalLength / 10.0)
            warning_ = "fStop " + std::to_string(p.fStop) + " but focusDistance " + std::to_string(p.focusDistance) +
                       " is not beyond the focal length: no depth of field";
        params_ = p;
    }
    // The shutter (just pulled) decides the interval the transform is sampled over.
    if (s.anyDirty({"transform", "shutter:open", "shutter:close"})) {
        params_.cameraToWorld = s.sampleTransform(s.time(), s.time()).front().matrix;
        shutterTransforms_.clear();
        if (params_.shutterClose > params_.shutterOpen)
            shutterTransforms_ = s.sampleTransform(s.time() + params_.shutterOpen, s.time() + params_.shutterClose);
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

Matrix4d Camera::cameraToWorldAt(double time) const {
    return shutterTransforms_.size() > 1 ? interpolateTransform(shutterTransforms_, time) : params_.cameraToWorld;
}

Matrix4d Camera::viewMatrix(std::array<double, 2> lensOffset, double time) const {
    Matrix4d lens = kIdentity;
    lens[12] = lensOffset[0];
    lens[13] = lensOffset[1];
    Matrix4d view = kIdentity;
    if (!invert(multiply(lens, cameraToWorldAt(time)), view)) return kIdentity;
    return view;
}

Matrix4d Camera::projectionMatrix(double imageAspect, std::array<double, 2> lensOffset,
                                  std::array<double, 2> ndcJitter) const {
    // Row-vector form: element [i * 4 + j] is the column-vector matrix's (j, i). A view-space point
    // at depth P moved by -lensOffset must land where it did: NDC x shifts by -c0 Lx / P, undone by
    // adding c0 Lx / P (times w = -z) through the z column; the same for y, and the jitter alike.
    Matrix4d p = projectionMatrix(imageAspect);
    if (params_.orthographic) {
        // w = 1: the jitter is a translation; an orthographic camera has no lens.
        p[12] += ndcJitter[0];
        p[13] += ndcJitter[1];
        return p;
    }
    double focus = params_.focusDistance > 0 ? params_.focusDistance : 1.0;
    p[8] -= p[0] * lensOffset[0] / focus + ndcJitter[0];
    p[9] -= p[5] * lensOffset[1] / focus + ndcJitter[1];
    return p;
}

passes::ThinLens Camera::thinLens(double imageAspect) const {
    const CameraParams& p = params_;
    if (p.orthographic) return {};
    // The same "fit" conform as the projection: the film spans the widened horizontal aperture.
    double filmWidth = std::max(p.horizontalAperture, p.verticalAperture * imageAspect);
    return {p.focalLength / 10.0, p.fStop, p.focusDistance, filmWidth / 10.0};
}

passes::ApertureShape Camera::apertureShape() const {
    return passes::apertureShape(params_.apertureBlades, params_.apertureRotation);
}

Matrix4d Camera::projectionMatrix(double imageAspect) const {
    const CameraParams& p = params_;
    double ha = p.horizontalAperture, va = p.verticalAperture;
    // Conform window policy "fit": widen whichever aperture the image aspect needs.
    if (imageAspect > ha / va) ha = va * imageAspect;
    else va = ha / imageAspect;
    // Depth 0 at the near end of the clipping range, 1 at the far end (schemas/camera_depth.h).
    const schema::DepthRow depth = schema::depthRow({p.orthographic, p.clippingRange[0], p.clippingRange[1]});
    // Column-vector form first (rows below), transposed at the end for the row-vector convention.
    Matrix4d c{};
    if (!p.orthographic) {
        c[0] = 2.0 * p.focalLength / ha;
        c[2] = 2.0 * p.horizontalApertureOffset / ha;
        c[5] = -2.0 * p.focalLength / va;  // Vulkan's y points down
        c[6] = -2.0 * p.verticalApertureOffset / va;
        c[10] = depth.scale;
        c[11] = depth.offset;
        c[14] = -1.0;
    } else {
        // Orthographic apertures are in tenths of a scene unit too.
        double w = ha / 10.0, h = va / 10.0;
        c[0] = 2.0 / w;
        c[3] = -2.0 * (p.horizontalApertureOffset / 10.0) / w;
        c[5] = -2.0 / h;
        c[7] = 2.0 * (p.verticalApertureOffset / 10.0) / h;
        c[10] = depth.scale;
        c[11] = depth.offset;
        c[15] = 1.0;
    }
    return transpose(c);
}

}  // namespace obscura::delegate
