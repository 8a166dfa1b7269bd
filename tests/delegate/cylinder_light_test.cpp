// UsdLux CylinderLight on a Lambert plane against the irradiance integral over its emitting side
// (caps do not emit), computed here by quadrature; normalize divides by the side's area under the
// transform's scale; an occluder's shadow; bad sizes skip the light; a USD stage's CylinderLight.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <cstdio>

namespace obscura::test {
namespace {

using Vec = std::array<double, 3>;

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// A tube of radiance `radiance` around the axis through `centre` along unit `axis`.
struct Tube {
    Vec centre, axis;
    double halfLength, radius, radiance;
};

// Irradiance at point p of the z = 0 plane (normal +Z) by the midpoint rule over the tube's side:
// E = L * integral of cos(emitter) cos(receiver) / d^2 dA. The tube is convex and its caps are
// opaque but do not emit, so a point of the side sees p exactly where its outward normal faces p.
double tubeIrradiance(const Tube& t, const Vec& p) {
    Vec u = std::fabs(t.axis[2]) < 0.9 ? Vec{t.axis[1], -t.axis[0], 0} : Vec{0, t.axis[2], -t.axis[1]};
    double ul = std::sqrt(dot(u, u));
    for (double& c : u) c /= ul;
    Vec v = {t.axis[1] * u[2] - t.axis[2] * u[1], t.axis[2] * u[0] - t.axis[0] * u[2], t.axis[0] * u[1] - t.axis[1] * u[0]};
    const int along = 1200, around = 720;
    const double dt = 2 * t.halfLength / along, dphi = 2 * kPi / around;
    double sum = 0;
    for (int i = 0; i < along; ++i) {
        double s = -t.halfLength + (i + 0.5) * dt;
        for (int j = 0; j < around; ++j) {
            double phi = (j + 0.5) * dphi;
            Vec n = {std::cos(phi) * u[0] + std::sin(phi) * v[0], std::cos(phi) * u[1] + std::sin(phi) * v[1],
                     std::cos(phi) * u[2] + std::sin(phi) * v[2]};
            Vec w;
            for (int k = 0; k < 3; ++k) w[k] = p[k] - (t.centre[k] + s * t.axis[k] + t.radius * n[k]);
            double d2 = dot(w, w), d = std::sqrt(d2);
            double emitter = dot(n, w) / d, receiver = -w[2] / d;
            if (emitter > 0 && receiver > 0) sum += emitter * receiver / d2;
        }
    }
    return t.radiance * sum * dt * t.radius * dphi;
}

// The light's transform: local X (its axis) turned by `tilt` radians about world Y, towards +Z.
Matrix tubeTransform(const Tube& t) {
    const Vec& x = t.axis;
    return {x[0], x[1], x[2], 0, 0, 1, 0, 0, -x[2], 0, x[0], 0, t.centre[0], t.centre[1], t.centre[2], 1};
}

void addTube(TestHost& host, const std::string& path, const Tube& t, std::map<std::string, HostValue> extra = {}) {
    extra.insert({{"inputs:intensity", HostValue::floatValue(float(t.radiance))},
                  {"inputs:length", HostValue::floatValue(float(2 * t.halfLength))},
                  {"inputs:radius", HostValue::floatValue(float(t.radius))},
                  {"inputs:specular", HostValue::floatValue(0.0f)}});
    host.addPrim("cylinderLight", path, extra, tubeTransform(t));
}

// Under the tube, beside it, off its end and beyond it.
const std::pair<int, int> kPixels[] = {{32, 32}, {20, 32}, {32, 12}, {10, 50}, {62, 40}, {2, 30}};

// The tube lit as a rectangle facing the point (light_evaluation.glsl cylinderSeenFrom) is exact
// for a long tube seen across its axis and within 1% of the integral wherever the point sees it
// from beside its length, for r / d up to 0.25 (d: the point's distance from the axis); seen
// from beyond an end it errs where the end's rim, not the tangent planes, bounds what is seen:
// within 2% for thin tubes (r / d <= 0.16 below: +0.5% and +1.7% measured, within the test's 1%
// and the accumulation's step), within 5% for thicker ones while the point lies more than 25
// degrees off the axis from the near end (measured +2.4% and +3.3%), and +12% seen nearly end on
// (19 degrees; left out below, and in docs/ARCHITECTURE.md).
void expectTubeLights(const Tube& tube, double beyondEndTolerance) {
    LitPlaneScene s;
    addTube(s.host, "/Tube", tube);
    auto color = s.renderColor();
    int beyond = 0;
    for (auto [x, y] : kPixels) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        Vec w = {p[0] - tube.centre[0], p[1] - tube.centre[1], p[2] - tube.centre[2]};
        double axial = dot(w, tube.axis), fromAxis = std::sqrt(std::max(0.0, dot(w, w) - axial * axial));
        double offAxisDegrees = std::atan2(fromAxis, std::fabs(axial) - tube.halfLength) * 180 / kPi;
        double l = kLitPlaneAlbedo / kPi * tubeIrradiance(tube, {p[0], p[1], p[2]});
        const float* c = &color[(size_t(y) * kWidth + x) * 4];
        std::printf("pixel (%d, %d): %.1f degrees off the axis from the near end, %+.2f%% of the integral\n", x, y,
                    offAxisDegrees, 100.0 * (c[0] / l - 1.0));
        if (std::fabs(axial) <= tube.halfLength) {
            expectRadiance(color, x, y, {l, l, l});
        } else if (offAxisDegrees > 25.0) {
            ++beyond;
            EXPECT_NEAR(c[0], l, beyondEndTolerance * l + smallFloatStep(float(l), 6)) << "pixel (" << x << ", " << y << ")";
        }
    }
    EXPECT_GE(beyond, 2);
}

TEST(CylinderLight, LevelTubeMatchesTheIntegralOverItsSide) {
    expectTubeLights({{0, 0, 0.5}, {1, 0, 0}, 0.6, 0.08, 4.0}, 0.02);
}

TEST(CylinderLight, TiltedThickerTubeMatchesTheIntegralOverItsSide) {
    const double tilt = 30 * kPi / 180;
    expectTubeLights({{0.1, -0.2, 0.7}, {std::cos(tilt), 0, std::sin(tilt)}, 0.5, 0.1, 2.0}, 0.05);
}

TEST(CylinderLight, NormalizeDividesByTheSideAreaUnderScale) {
    LitPlaneScene s;
    const double intensity = 3.0, halfLength = 0.4, radius = 0.05, height = 0.6;
    Matrix m = translation(0, 0, height);
    m[0] = 2.0;   // local X: twice as long
    m[5] = 1.5;   // local Y and Z: the radius takes the larger scale
    m[10] = 1.2;
    s.host.addPrim("cylinderLight", "/Tube",
                   {{"inputs:intensity", HostValue::floatValue(float(intensity))},
                    {"inputs:length", HostValue::floatValue(float(2 * halfLength))},
                    {"inputs:radius", HostValue::floatValue(float(radius))},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   m);
    auto color = s.renderColor();
    Tube scaled{{0, 0, height}, {1, 0, 0}, 2.0 * halfLength, 1.5 * radius, 0.0};
    scaled.radiance = intensity / (2 * kPi * scaled.radius * 2 * scaled.halfLength);
    for (auto [x, y] : {std::pair{32, 32}, std::pair{45, 20}}) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double l = kLitPlaneAlbedo / kPi * tubeIrradiance(scaled, {p[0], p[1], p[2]});
        expectRadiance(color, x, y, {l, l, l});
    }
}

// A plate under the tube, as long as the image and 0.6 wide, hides the whole tube from the plane
// below its middle; beside the plate's shadow the plane sees all of the tube.
TEST(CylinderLight, PlateCastsTheTubesShadow) {
    LitPlaneScene s;
    const Tube tube{{0, 0, 0.5}, {1, 0, 0}, 0.6, 0.05, 4.0};
    addTube(s.host, "/Tube", tube);
    addMaterial(s.host, "/Looks/Plate", {0.5f, 0.5f, 0.5f});
    Matrix plate = translation(0, 0, 0.25);
    plate[0] = 2.0;
    plate[5] = 0.3;
    addPlane(s.host, "/Plate", "/Looks/Plate", 1.0, plate);
    auto color = s.renderColor();
    // The camera above sees the plane beside the plate where |y| > 0.3 * 5 / 4.75 = 0.32. Lines
    // from a plane point at y to the tube (|y| <= 0.05 at z = 0.5) cross the plate's height,
    // z = 0.25, halfway: the plate hides all of the tube from y < 0.55 and none of it from
    // y > 0.65. The soft-shadow filter widens the tube's penumbra to that of the disc of its
    // projected area (radius 0.195: y from 0.41 to 0.79; docs/ARCHITECTURE.md), so rows well
    // outside both are tested: lit as without the plate (y > 0.9), dark (y < 0.38).
    for (int y : {1, 3}) {
        for (int x : {20, 32, 44}) {
            auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
            ASSERT_GT(p[1], 0.9);
            double l = kLitPlaneAlbedo / kPi * tubeIrradiance(tube, {p[0], p[1], p[2]});
            expectRadiance(color, x, y, {l, l, l});
        }
    }
    for (int y : {20, 21}) {
        for (int x : {24, 32, 40}) {
            auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
            ASSERT_GT(p[1], 0.33);
            ASSERT_LT(p[1], 0.38);
            double unshadowed = kLitPlaneAlbedo / kPi * tubeIrradiance(tube, {p[0], p[1], p[2]});
            const float* c = &color[(size_t(y) * kWidth + x) * 4];
            EXPECT_LT(c[0], 0.02 * unshadowed) << "pixel (" << x << ", " << y << ") at y = " << p[1];
        }
    }
}

TEST(CylinderLight, SizesThatAreNotPositiveSkipTheLight) {
    for (const char* attribute : {"inputs:length", "inputs:radius"}) {
        LitPlaneScene s;
        addTube(s.host, "/Tube", {{0, 0, 0.5}, {1, 0, 0}, 0.6, 0.08, 4.0}, {{attribute, HostValue::floatValue(-1.0f)}});
        s.host.expectError("skipped prim /Tube: inputs:length and inputs:radius must be positive");
        EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
        // The plane still renders, unlit.
        auto color = s.host.readFloats("/Buffers/color");
        expectRadiance(color, 32, 32, {0, 0, 0});
    }
}

// From USD text through the harness: the CylinderLight prim lights like the host-built one.
TEST(CylinderLight, UsdStageLightsThePlane) {
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + R"(
def Mesh "Ground"
{
    point3f[] points = [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
}
def CylinderLight "Tube"
{
    float inputs:intensity = 4
    float inputs:length = 1.2
    float inputs:radius = 0.08
    float inputs:specular = 0
    double3 xformOp:translate = (0, 0, 0.5)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
)",
                                                  "tube.usda"));
    std::vector<float> color = scene.renderAov("color", 4), albedo = scene.renderAlbedo();
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
    EXPECT_FALSE(scene.warned("not supported"));
    const Tube tube{{0, 0, 0.5}, {1, 0, 0}, 0.6, 0.08, 4.0};
    for (auto [x, y] : {std::pair{32, 32}, std::pair{20, 40}}) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double a = albedo[(size_t(y) * kWidth + x) * 3];
        ASSERT_GT(a, 0.1);
        double l = a / kPi * tubeIrradiance(tube, {p[0], p[1], p[2]});
        expectRadiance(color, x, y, {l, l, l});
    }
}

}  // namespace
}  // namespace obscura::test
