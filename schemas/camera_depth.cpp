#include "schemas/camera_depth.h"

#include "schemas/schema.h"

#include <limits>

namespace obscura::schema {

CameraDepth defaultCameraDepth() {
    return {defaultToken("camera", "projection") == "orthographic", defaultNumber("camera", "clippingRange", 0),
            defaultNumber("camera", "clippingRange", 1)};
}

DepthRow depthRow(const CameraDepth& c) {
    const double n = c.nearClip, f = c.farClip;
    // Perspective: z = -n maps to 0 and z = -f to 1 after the divide by -z; orthographic: linearly.
    if (c.orthographic) return {-1.0 / (f - n), -n / (f - n)};
    return {f / (n - f), n * f / (n - f)};
}

double viewDistance(double clipDepth, const CameraDepth& c) {
    if (clipDepth >= 1.0) return std::numeric_limits<double>::infinity();
    if (c.orthographic) return c.nearClip + clipDepth * (c.farClip - c.nearClip);
    // Inverse of depth = (scale z + offset) / -z at distance -z.
    const DepthRow row = depthRow(c);
    return row.offset / (clipDepth + row.scale);
}

}  // namespace obscura::schema
