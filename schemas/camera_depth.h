// The camera's depth in terms of its schema: the "depth" AOV (include/obscura/obscura.h) is Vulkan
// clip-space depth, 0 at the near end of clippingRange and 1 at the far end, hyperbolic in the
// distance along the view axis for a perspective projection and linear for an orthographic one.
// The delegate's projection and a host turning the AOV back into distances (the harness's EXR Z)
// share these, with the schema's defaults for a camera that authors neither attribute.
#pragma once

#include <array>

namespace obscura::schema {

struct CameraDepth {
    bool orthographic;  // projection
    double nearClip;    // clippingRange
    double farClip;
};

// projection and clippingRange as the camera schema defaults them.
CameraDepth defaultCameraDepth();

// The projection's depth row (column-vector form): clip z = scale * z + offset for a view-space z
// (negative in front of the camera), divided by w = -z (perspective) or 1 (orthographic).
struct DepthRow {
    double scale;
    double offset;
};
DepthRow depthRow(const CameraDepth& camera);

// Distance along the view axis of a clip-space depth in [0, 1]; infinity at 1 (nothing drew).
double viewDistance(double clipDepth, const CameraDepth& camera);

}  // namespace obscura::schema
