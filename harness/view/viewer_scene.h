// What the viewer adds to the scene it shows: its free camera and its render buffers, answered by
// the viewer itself, in front of the stage's scene host. The callbacks the delegate holds stay the
// same when the scene is read again from disk: only the host behind them changes.
#pragma once

#include "harness/usd_scene_host.h"
#include "harness/view/orbit_camera.h"

#include <obscura/obscura.h>

#include <map>
#include <string>
#include <vector>

namespace obscura::harness::view {

// The free camera's lens (UsdGeomCamera's attributes, tenths of a scene unit for the lens).
struct ViewerLens {
    double focalLength = 35.0;
    double horizontalAperture = 20.955;
    double fStop = 0.0;  // 0: no depth of field (USD's default)
    double focusDistance = 10.0;
    int apertureBlades = 0;  // 0: a round aperture
    double nearClip = 0.1, farClip = 10000.0;
};

class ViewerScene {
public:
    static constexpr const char* kCameraPath = "/ObscuraViewer/Camera";

    explicit ViewerScene(UsdSceneHost& host) : host_(&host) {}
    const ObscuraSceneDelegate& sceneDelegate();
    void setHost(UsdSceneHost& host) { host_ = &host; }
    UsdSceneHost& host() { return *host_; }

    OrbitCamera camera;
    ViewerLens lens;
    double aspect = 1.0;  // width / height of the viewport (the vertical aperture follows it)
    // The vertical field of view of the free camera.
    double verticalFov() const;

    // The render buffer named `name`, in the format of `aov`, at the viewer's size; returns its path.
    std::string renderBuffer(const std::string& name, const std::string& aov, int width, int height);

private:
    static ObscuraStatus getValue(void* user, const char* path, const char* attribute, double time, ObscuraValue* out);
    static ObscuraStatus getInterpolation(void* user, const char* path, const char* attribute, ObscuraInterpolation* out);
    static ObscuraStatus sampleTransform(void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                         double* times, double* matrices, uint32_t* count);
    ObscuraStatus cameraValue(const std::string& attribute, ObscuraValue* out);

    UsdSceneHost* host_;
    ObscuraSceneDelegate delegate_{};
    struct Buffer {
        int width, height;
        std::string format;
    };
    std::map<std::string, Buffer> buffers_;
    // Backing for the last value returned (valid until the next callback, per the ABI).
    std::vector<double> doubles_;
    std::vector<float> floats_;
    std::vector<int32_t> ints_;
    std::string token_;
    const char* tokenPointer_ = nullptr;
};

}  // namespace obscura::harness::view
