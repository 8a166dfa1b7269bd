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
    if (s.getBool("inputs:enableColorTemperature")) {
        auto tint = blackbodyColor(s.getDouble("inputs:colorTemperature"));
        for (size_t i = 0; i < 3; ++i) color[i] *= tint[i];
    }
    castsShadows_ = type_ != passes::LightType::Dome && s.getBool("inputs:shadow:enable");
    passes::LightData d{};
    d.factors = {s.getFloat("inputs:diffuse"), s.getFloat("inputs:specular"), 0.0f, 0.0f};
    double scale = 1.0;
    warning_.clear();
    if (type_ == passes::LightType::Dome) {
        // XXX: environment textures (prefiltered specular, convolved diffuse) arrive with the
        // lighting issue; until then the dome lights with its constant colour.
        if (!s.getToken("inputs:texture:file").empty())
            warning_ = "inputs:texture:file is not supported yet; the dome uses its constant colour";
        d.positionType = {0, 0, 0, float(passes::LightType::Dome)};
    } else if (type_ == passes::LightType::Distant) {
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

std::array<float, 3> blackbodyColor(double kelvin) {
    double t = std::clamp(kelvin, 1000.0, 40000.0);
    // Planckian locus in CIE 1960 uv (Krystek 1985), then xy and XYZ with Y = 1.
    double u = (0.860117757 + 1.54118254e-4 * t + 1.28641212e-7 * t * t) / (1.0 + 8.42420235e-4 * t + 7.08145163e-7 * t * t);
    double v = (0.317398726 + 4.22806245e-5 * t + 4.20481691e-8 * t * t) / (1.0 - 2.89741816e-5 * t + 1.61456053e-7 * t * t);
    double x = 3.0 * u / (2.0 * u - 8.0 * v + 4.0), y = 2.0 * v / (2.0 * u - 8.0 * v + 4.0);
    double X = x / y, Y = 1.0, Z = (1.0 - x - y) / y;
    // XYZ to linear Rec.709 (D65).
    std::array<double, 3> rgb = {3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z,
                                 -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                                 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z};
    for (auto& c : rgb) c = std::max(c, 0.0);
    double luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    return {float(rgb[0] / luminance), float(rgb[1] / luminance), float(rgb[2] / luminance)};
}

}  // namespace obscura::delegate
