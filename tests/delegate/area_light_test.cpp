// UsdLux area and shaped lights on a Lambert plane against closed-form irradiance: a rectangle
// and a disk parallel to the plane (configuration factors of a differential area to a parallel
// rectangle and disk, e.g. Howell's catalogue, cases B-3 and B-4), a tilted and an upright disk
// against the quadrature of their irradiance integral, the ShapingAPI cone and its softness,
// one-sided emission, normalize.
#include "tests/delegate/render_fixture.h"


namespace obscura::test {
namespace {

// Light pointing straight down (-Z, its default) at (x, y, z).
Matrix downAt(double x, double y, double z) { return translation(x, y, z); }

// Configuration factor from a point to a parallel rectangle with one corner above it, sides
// a and b at height h (odd in a and in b, so signed sides add up any placement).
double cornerFactor(double a, double b, double h) {
    double A = a / h, B = b / h;
    double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
    return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * kPi);
}

// Irradiance at plane point p from a parallel rectangle of radiance L centred above the origin.
double rectIrradiance(double radiance, double halfWidth, double halfHeight, double h, std::array<double, 3> p) {
    double f = 0;
    for (double sx : {-1.0, 1.0})
        for (double sy : {-1.0, 1.0}) f += cornerFactor(halfWidth + sx * p[0], halfHeight + sy * p[1], h);
    return kPi * radiance * f;
}

// A sphere light straight above the plane's origin at `height`, seen from the plane point under
// pixel (x, y): the cosine of its angle off the vertical (= off the light's -Z axis, and the
// surface's cos theta) and the Lambert radiance before any shaping, albedo/pi * pi L r^2/d^2 cos.
struct BulbOverhead {
    double cosTheta, radiance;
};
BulbOverhead bulbOverhead(int x, int y, double height, double radius, double radiance) {
    auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
    double d2 = p[0] * p[0] + p[1] * p[1] + height * height;
    double cosTheta = height / std::sqrt(d2);
    return {cosTheta, kLitPlaneAlbedo * radiance * radius * radius / d2 * cosTheta};
}

const std::pair<int, int> kPixels[] = {{32, 32}, {10, 20}, {50, 60}, {3, 3}, {62, 40}};

// A rectangle light of `radiance` pointing down from (x, y, height) against the parallel
// rectangle's closed form at each of kPixels.
void expectParallelRectangle(double radiance, double halfWidth, double halfHeight, double x0, double y0,
                             double height) {
    LitPlaneScene s;
    s.host.addPrim("rectLight", "/Panel",
                   {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                    {"inputs:width", HostValue::floatValue(float(2 * halfWidth))},
                    {"inputs:height", HostValue::floatValue(float(2 * halfHeight))},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   downAt(x0, y0, height));
    auto color = s.renderColor();
    for (auto [x, y] : kPixels) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double l = kLitPlaneAlbedo / kPi * rectIrradiance(radiance, halfWidth, halfHeight, height, {p[0] - x0, p[1] - y0, p[2]});
        expectRadiance(color, x, y, {l, l, l});
    }
}

TEST(AreaLight, RectangleMatchesTheParallelRectangleFactor) { expectParallelRectangle(3.0, 1.0, 0.5, 0.0, 0.0, 0.75); }

TEST(AreaLight, NormalizedRectangleDividesByItsArea) {
    LitPlaneScene s;
    const double intensity = 8.0, halfWidth = 0.5, halfHeight = 0.25, height = 1.0, scale = 2.0;
    // The transform's scale doubles both sides: the area, and so the divisor, is 4x larger.
    Matrix m = downAt(0, 0, height);
    m[0] = m[5] = scale;
    s.host.addPrim("rectLight", "/Panel",
                   {{"inputs:intensity", HostValue::floatValue(float(intensity))},
                    {"inputs:width", HostValue::floatValue(float(2 * halfWidth))},
                    {"inputs:height", HostValue::floatValue(float(2 * halfHeight))},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   m);
    auto color = s.renderColor();
    double radiance = intensity / (4 * halfWidth * halfHeight * scale * scale);
    auto p = planePointAtPixel(20, 40, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
    double l = kLitPlaneAlbedo / kPi * rectIrradiance(radiance, halfWidth * scale, halfHeight * scale, height, p);
    expectRadiance(color, 20, 40, {l, l, l});
}

TEST(AreaLight, DiskMatchesTheParallelDiskFactor) {
    LitPlaneScene s;
    const double radiance = 2.0, radius = 0.6, height = 0.5;
    s.host.addPrim("diskLight", "/Disk",
                   {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                    {"inputs:radius", HostValue::floatValue(float(radius))},
                    {"inputs:color", HostValue::float3(1.0f, 0.5f, 0.25f)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   downAt(0, 0, height));
    auto color = s.renderColor();
    for (auto [x, y] : kPixels) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double l = kLitPlaneAlbedo / kPi * diskIrradiance(radiance, radius, height, std::hypot(p[0], p[1]));
        expectRadiance(color, x, y, {l, l * 0.5, l * 0.25});
    }
}

// Irradiance at plane point p (normal +Z) from a uniform disk of radiance L, centre `centre`,
// radius r, spanned by the unit axes u and v and emitting along `axis`: E = L * integral of
// cos(emitter) cos(receiver) / d^2 over the disk's area (the part above p's horizon), by the
// midpoint rule on a fine polar grid.
double diskIrradianceByQuadrature(double radiance, std::array<double, 3> centre, double r, std::array<double, 3> u,
                                  std::array<double, 3> v, std::array<double, 3> axis, std::array<double, 3> p) {
    const int rings = 400, sectors = 800;
    double sum = 0;
    for (int i = 0; i < rings; ++i) {
        double rho = (i + 0.5) / rings * r, ring = rho * (r / rings) * (2 * kPi / sectors);
        for (int j = 0; j < sectors; ++j) {
            double phi = (j + 0.5) / sectors * 2 * kPi, c = std::cos(phi) * rho, s = std::sin(phi) * rho;
            std::array<double, 3> d;
            for (int k = 0; k < 3; ++k) d[size_t(k)] = p[size_t(k)] - (centre[size_t(k)] + c * u[size_t(k)] + s * v[size_t(k)]);
            double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], len = std::sqrt(d2);
            double cosEmitter = (d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2]) / len, cosReceiver = -d[2] / len;
            if (cosEmitter > 0 && cosReceiver > 0) sum += cosEmitter * cosReceiver / d2 * ring;
        }
    }
    return radiance * sum;
}

// A disk light of `radiance` along `direction` at `centre` against the quadrature of its exact circle.
void expectDiskAlong(std::array<double, 3> direction, std::array<double, 3> centre, double radius,
                     double radiance = 2.0) {
    LitPlaneScene s;
    Matrix m = lightPointingAlong(direction);
    m[12] = centre[0], m[13] = centre[1], m[14] = centre[2];
    s.host.addPrim("diskLight", "/Disk",
                   {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                    {"inputs:radius", HostValue::floatValue(float(radius))},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   m);
    auto color = s.renderColor();
    std::array<double, 3> u{m[0], m[1], m[2]}, v{m[4], m[5], m[6]}, axis{-m[8], -m[9], -m[10]};
    for (auto [x, y] : kPixels) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double l = kLitPlaneAlbedo / kPi * diskIrradianceByQuadrature(radiance, centre, radius, u, v, axis, p);
        expectRadiance(color, x, y, {l, l, l});
    }
}

TEST(AreaLight, TiltedDiskMatchesItsIrradianceIntegral) {
    // Tilted 37 degrees off the vertical, wholly above the plane: the closed form's oblique case.
    expectDiskAlong({0.6, 0.0, -0.8}, {-0.3, 0.2, 0.9}, 0.5);
}

TEST(AreaLight, UprightDiskIsClippedAtTheHorizon) {
    // Standing across the plane, its lower part below the ground: the clipped polygon's case.
    expectDiskAlong({0.0, -1.0, 0.0}, {0.1, 0.7, 0.3}, 0.6);
}

// Small lights are lit as point Lambert emitters beyond 32 half diagonals
// (light_evaluation.glsl AREA_LIGHT_FAR_FIELD): the plane's points under these lie 1.67 to 2.42 m
// from the disk, whose form changes at 1.81 m, and all beyond the rectangle's 1.15 m.
TEST(AreaLight, SmallTiltedDiskMatchesItsIrradianceIntegralNearAndFar) {
    expectDiskAlong({0.6, 0.0, -0.8}, {0.4, -0.3, 1.6}, 0.04, 2000.0);
}

TEST(AreaLight, SmallRectangleMatchesTheParallelRectangleFactorFar) {
    expectParallelRectangle(3000.0, 0.03, 0.02, 0.2, -0.1, 1.2);
}

TEST(AreaLight, EmitsFromItsFrontFaceOnly) {
    LitPlaneScene s;
    Matrix up = downAt(0, 0, 0.5);
    up[5] = up[10] = -1;  // rotated half a turn about X: emits along +Z, away from the plane
    s.host.addPrim("rectLight", "/Panel", {{"inputs:intensity", HostValue::floatValue(10.0f)}}, up);
    s.host.addPrim("diskLight", "/Disk", {{"inputs:intensity", HostValue::floatValue(10.0f)}}, up);
    auto color = s.renderColor();
    for (auto [x, y] : kPixels) expectRadiance(color, x, y, {0, 0, 0});
}

TEST(AreaLight, UprightRectangleIsClippedAtTheHorizon) {
    // A panel standing upright across the plane, its lower half below the ground, lights the
    // plane through its upper half only. For a point in front of the panel the clipped polygon's
    // factor is that of perpendicular rectangles with an edge at the receiver's level (Howell
    // B-2): F = (atan(w/d) - d/sqrt(d^2+c^2) atan(w/sqrt(d^2+c^2))) / 2pi for each side.
    LitPlaneScene s;
    const double radiance = 4.0, halfAcross = 1.5, halfUp = 1.0, distance = 0.6;
    Matrix m = lightPointingAlong({0, -1, 0});  // emits towards -Y; local X is world Z, local Y world X
    m[12] = 0, m[13] = distance, m[14] = 0;
    s.host.addPrim("rectLight", "/Panel",
                   {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                    {"inputs:width", HostValue::floatValue(float(2 * halfUp))},
                    {"inputs:height", HostValue::floatValue(float(2 * halfAcross))},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   m);
    auto color = s.renderColor();
    for (int y : {40, 50, 60}) {
        auto p = planePointAtPixel(32, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double d = distance - p[1], c = halfUp, slant = std::sqrt(d * d + c * c);
        auto side = [&](double w) { return (std::atan(w / d) - d / slant * std::atan(w / slant)) / (2 * kPi); };
        double f = side(halfAcross - p[0]) + side(halfAcross + p[0]);
        double l = kLitPlaneAlbedo * radiance * f;
        expectRadiance(color, 32, y, {l, l, l});
    }
}

TEST(AreaLight, SpotConeCutsAndSoftensTheSphereLight) {
    const double height = 2.0, radius = 0.05, radiance = 2000.0, cone = 15.0;
    for (double softness : {0.0, 0.5}) {
        LitPlaneScene s;
        s.host.addPrim("sphereLight", "/Spot",
                       {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                        {"inputs:radius", HostValue::floatValue(float(radius))},
                        {"inputs:shaping:cone:angle", HostValue::floatValue(float(cone))},
                        {"inputs:shaping:cone:softness", HostValue::floatValue(float(softness))},
                        {"inputs:specular", HostValue::floatValue(0.0f)}},
                       downAt(0, 0, height));
        auto color = s.renderColor();
        for (auto [x, y] : kPixels) {
            BulbOverhead bulb = bulbOverhead(x, y, height, radius, radiance);
            double offAxis = std::acos(bulb.cosTheta), cutoff = cone * kPi / 180, start = cutoff * (1 - softness);
            double t = std::clamp((offAxis - start) / (cutoff - start), 0.0, 1.0);
            double attenuation = offAxis > cutoff ? 0.0 : softness == 0.0 ? 1.0 : 1.0 - t * t * (3 - 2 * t);
            double l = bulb.radiance * attenuation;
            expectRadiance(color, x, y, {l, l, l});
        }
    }
}

TEST(AreaLight, FocusNarrowsTheSpread) {
    LitPlaneScene s;
    const double height = 1.5, radius = 0.05, radiance = 500.0, focus = 4.0;
    s.host.addPrim("sphereLight", "/Bulb",
                   {{"inputs:intensity", HostValue::floatValue(float(radiance))},
                    {"inputs:radius", HostValue::floatValue(float(radius))},
                    {"inputs:shaping:focus", HostValue::floatValue(float(focus))},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   downAt(0, 0, height));
    auto color = s.renderColor();
    for (auto [x, y] : kPixels) {
        BulbOverhead bulb = bulbOverhead(x, y, height, radius, radiance);
        double l = bulb.radiance * std::pow(bulb.cosTheta, focus);
        expectRadiance(color, x, y, {l, l, l});
    }
}

}  // namespace
}  // namespace obscura::test
