#include "harness/view/viewer_scene.h"

#include <cmath>

namespace obscura::harness::view {
namespace {

bool isViewerPrim(const char* path) { return std::string(path).rfind("/ObscuraViewer/", 0) == 0; }

}  // namespace

const ObscuraSceneDelegate& ViewerScene::sceneDelegate() {
    delegate_ = {OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE, nullptr, sizeof(ObscuraSceneDelegate), 0, this,
                 &ViewerScene::getValue, &ViewerScene::getInterpolation, &ViewerScene::sampleTransform};
    return delegate_;
}

double ViewerScene::verticalFov() const {
    return 2.0 * std::atan(0.5 * lens.horizontalAperture / aspect / lens.focalLength);
}

std::string ViewerScene::renderBuffer(const std::string& name, const std::string& aov, int width, int height) {
    std::string path = "/ObscuraViewer/Buffers/" + name;
    buffers_[path] = {width, height, aovBufferFormat(aov)};
    return path;
}

ObscuraStatus ViewerScene::cameraValue(const std::string& attribute, ObscuraValue* out) {
    auto number = [&](double v) {
        floats_ = {float(v)};
        *out = {OBSCURA_VALUE_FLOAT, 0, 1, floats_.data()};
        return OBSCURA_OK;
    };
    if (attribute == "focalLength") return number(lens.focalLength);
    if (attribute == "horizontalAperture") return number(lens.horizontalAperture);
    if (attribute == "verticalAperture") return number(lens.horizontalAperture / aspect);
    if (attribute == "fStop") return number(lens.fStop);
    if (attribute == "focusDistance") return number(lens.focusDistance);
    if (attribute == "obscura:apertureBlades") {
        ints_ = {lens.apertureBlades};
        *out = {OBSCURA_VALUE_INT, 0, 1, ints_.data()};
        return OBSCURA_OK;
    }
    if (attribute == "clippingRange") {
        floats_ = {float(lens.nearClip), float(lens.farClip)};
        *out = {OBSCURA_VALUE_FLOAT2, 0, 1, floats_.data()};
        return OBSCURA_OK;
    }
    return OBSCURA_ERROR_NOT_FOUND;  // the schema's defaults
}

ObscuraStatus ViewerScene::getValue(void* user, const char* path, const char* attribute, double time, ObscuraValue* out) {
    auto* self = static_cast<ViewerScene*>(user);
    if (!isViewerPrim(path)) {
        const ObscuraSceneDelegate& host = self->host_->sceneDelegate();
        return host.getValue(host.userData, path, attribute, time, out);
    }
    if (std::string(path) == kCameraPath) return self->cameraValue(attribute, out);
    auto buffer = self->buffers_.find(path);
    if (buffer == self->buffers_.end()) return OBSCURA_ERROR_NOT_FOUND;
    if (std::string(attribute) == "dimensions") {
        self->ints_ = {buffer->second.width, buffer->second.height};
        *out = {OBSCURA_VALUE_INT2, 0, 1, self->ints_.data()};
        return OBSCURA_OK;
    }
    if (std::string(attribute) == "format") {
        self->token_ = buffer->second.format;
        self->tokenPointer_ = self->token_.c_str();
        *out = {OBSCURA_VALUE_TOKEN, 0, 1, &self->tokenPointer_};
        return OBSCURA_OK;
    }
    return OBSCURA_ERROR_NOT_FOUND;
}

ObscuraStatus ViewerScene::getInterpolation(void* user, const char* path, const char* attribute,
                                            ObscuraInterpolation* out) {
    auto* self = static_cast<ViewerScene*>(user);
    if (isViewerPrim(path)) return OBSCURA_ERROR_NOT_FOUND;
    const ObscuraSceneDelegate& host = self->host_->sceneDelegate();
    return host.getInterpolation(host.userData, path, attribute, out);
}

ObscuraStatus ViewerScene::sampleTransform(void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                           double* times, double* matrices, uint32_t* count) {
    auto* self = static_cast<ViewerScene*>(user);
    if (!isViewerPrim(path)) {
        const ObscuraSceneDelegate& host = self->host_->sceneDelegate();
        return host.sampleTransform(host.userData, path, t0, t1, maxSamples, times, matrices, count);
    }
    if (maxSamples == 0) return OBSCURA_ERROR_NOT_FOUND;
    times[0] = t0;
    const Matrix4 m = self->camera.matrix();
    std::copy(m.begin(), m.end(), matrices);
    *count = 1;
    return OBSCURA_OK;
}

}  // namespace obscura::harness::view
