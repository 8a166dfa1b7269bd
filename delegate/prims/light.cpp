#include "delegate/prims/light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::delegate {

void Light::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext&) {
    if (bits & OBSCURA_DIRTY_TRANSFORM) transform_ = s.sampleTransform(s.time(), s.time()).front().matrix;
    if (bits & OBSCURA_DIRTY_VISIBILITY) visible_ = s.getToken("visibility") != "invisible";
    if (!(bits & (OBSCURA_DIRTY_PARAMS | OBSCURA_DIRTY_TRANSFORM))) return;

    const double pi = std::numbers::pi;
    double intensity = s.getDouble("inputs:intensity") * std::exp2(s.getDouble("inputs:exposure"));
    auto color = s.getFloat3("inputs:color");
    bool normalize = s.getBool("inputs:normalize");
    if (s.getBool("inputs:enableColorTemperature"))
        // XXX: colour temperature arrives with the lighting work; the light keeps inputs:color.
        (void)s.getDouble("inputs:colorTemperature");
    passes::LightData d{};
    d.factors = {s.getFloat("inputs:diffuse"), s.getFloat("inputs:specular"), 0.0f, 0.0f};
    double scale = 1.0;
    if (type_ == passes::LightType::Distant) {
        double angle = s.getDouble("inputs:angle") * pi / 180.0;
        double solidAngle = 2.0 * pi * (1.0 - std::cos(angle / 2.0));
        scale = normalize ? 1.0 : solidAngle;
        // UsdLux lights emit along their local -Z axis.
        Vec3d dir = normalized(transformDirection({0, 0, -1}, transform_));
        d.positionType = {0, 0, 0, float(passes::LightType::Distant)};
        d.directionAngle = {float(dir[0]), float(dir[1]), float(dir[2]), float(angle / 2.0)};
    } else {
        // The radius scales with the transform (largest axis scale).
        double axisScale = std::max({length(transformDirection({1, 0, 0}, transform_)),
                                     length(transformDirection({0, 1, 0}, transform_)),
                                     length(transformDirection({0, 0, 1}, transform_))});
        double radius = s.getDouble("inputs:radius") * axisScale;
        if (radius <= 0) throw PrimDataError(s.path() + ": inputs:radius must be positive");
        if (normalize) scale = 1.0 / (4.0 * pi * radius * radius);
        Vec3d pos = transformPoint({0, 0, 0}, transform_);
        d.positionType = {float(pos[0]), float(pos[1]), float(pos[2]), float(passes::LightType::Sphere)};
        d.directionAngle = {0, 0, 0, 0};
        d.factors[2] = s.getBool("treatAsPoint") ? 1.0f : 0.0f;
        d.radiance[3] = float(radius);
    }
    for (int i = 0; i < 3; ++i) d.radiance[size_t(i)] = float(intensity * scale * color[size_t(i)]);
    data_ = d;
}

}  // namespace obscura::delegate
