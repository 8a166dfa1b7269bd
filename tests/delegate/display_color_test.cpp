// displayColor and displayOpacity shade a prim that has no material, as Hydra's fallback material
// does (Storm): one test per interpolation. A two-face mesh (left and right halves, sharing the
// middle column of points) fills the view of a camera at (0, 0, 5) looking down -Z, lit head-on by
// a normalized distant light with no specular, so a pixel's radiance is Lambert's
// displayColor / pi * E; colours are values 8-bit sRGB (the albedo G-buffer target) holds exactly.
// A PointInstancer's displayColor and displayOpacity primvars colour each instance in place of its
// prototype's (Hydra's instance primvars); curves and points take them as meshes do.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

constexpr double kIrradiance = 3.0;
using Rgb = std::array<float, 3>;
const Rgb kRed{srgb8Exact(200), srgb8Exact(40), srgb8Exact(40)};
const Rgb kBlue{srgb8Exact(40), srgb8Exact(40), srgb8Exact(200)};
const Rgb kGreen{srgb8Exact(40), srgb8Exact(200), srgb8Exact(40)};
constexpr float kHalf = 1.2f;  // beyond the view's half-size at z = 0 (1.04775)

struct DisplayColorScene {
    TestHost host;
    DisplayColorScene() {
        addLitPlaneViewAndSun(host, kIrradiance);
    }
    // Points: bottom row left to right (0, 1, 2), top row (3, 4, 5); faces: left, right.
    void addHalves(const std::vector<Rgb>& colours, ObscuraInterpolation interpolation,
                   std::optional<float> opacity = std::nullopt) {
        std::map<std::string, HostValue> values = {
            {"points", HostValue::points({{-kHalf, -kHalf, 0}, {0, -kHalf, 0}, {kHalf, -kHalf, 0},
                                          {-kHalf, kHalf, 0}, {0, kHalf, 0}, {kHalf, kHalf, 0}})},
            {"faceVertexCounts", HostValue::intArray({4, 4})},
            {"faceVertexIndices", HostValue::intArray({0, 1, 4, 3, 1, 2, 5, 4})},
            {"subdivisionScheme", HostValue::token("none")},
            {"primvars:displayColor", HostValue::points(colours)},
        };
        if (opacity) {
            HostValue o;
            o.type = OBSCURA_VALUE_FLOAT;
            o.isArray = true;
            o.floats = {*opacity};
            values["primvars:displayOpacity"] = o;
        }
        host.addPrim("mesh", "/Halves", values);
        host.setInterpolation("/Halves", "primvars:displayColor", interpolation);
        if (opacity) host.setInterpolation("/Halves", "primvars:displayOpacity", OBSCURA_INTERPOLATION_CONSTANT);
    }
    std::vector<float> render() {
        EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
        return host.readFloats("/Buffers/color");
    }
};

std::array<double, 3> lambert(const Rgb& albedo, double scale = 1.0) {
    return {albedo[0] / kPi * kIrradiance * scale, albedo[1] / kPi * kIrradiance * scale,
            albedo[2] / kPi * kIrradiance * scale};
}

TEST(DisplayColor, ConstantColoursTheWholePrim) {
    DisplayColorScene s;
    s.addHalves({kRed}, OBSCURA_INTERPOLATION_CONSTANT);
    auto color = s.render();
    for (auto [x, y] : {std::pair{8, 8}, {32, 32}, {56, 60}}) expectRadiance(color, x, y, lambert(kRed));
}

TEST(DisplayColor, UniformColoursEachFace) {
    DisplayColorScene s;
    s.addHalves({kRed, kBlue}, OBSCURA_INTERPOLATION_UNIFORM);
    auto color = s.render();
    for (auto [x, y] : {std::pair{4, 8}, {28, 56}}) expectRadiance(color, x, y, lambert(kRed));
    for (auto [x, y] : {std::pair{36, 8}, {60, 56}}) expectRadiance(color, x, y, lambert(kBlue));
}

TEST(DisplayColor, FaceVaryingColoursEachCornerApartFromItsNeighbours) {
    // Both faces share the middle points, yet each face's corners hold its own colour: the split
    // at the middle stays sharp (vertex interpolation could not do this).
    DisplayColorScene s;
    s.addHalves({kGreen, kGreen, kGreen, kGreen, kRed, kRed, kRed, kRed}, OBSCURA_INTERPOLATION_FACE_VARYING);
    auto color = s.render();
    for (auto [x, y] : {std::pair{4, 8}, {31, 40}}) expectRadiance(color, x, y, lambert(kGreen));
    for (auto [x, y] : {std::pair{32, 8}, {60, 40}}) expectRadiance(color, x, y, lambert(kRed));
}

// Where along x in [-kHalf, kHalf] pixel column x sees the plane z = 0, from 0 to 1.
double acrossAt(int x) {
    return (planePointAtPixel(x, 32, kLitPlaneCameraDistance, kLitPlaneTanHalfFov)[0] + kHalf) / (2.0 * kHalf);
}

// Red on the left edge, blue on the right: the colour is affine in x, which the triangles
// reproduce exactly. The G-buffer keeps the interpolated albedo to one 8-bit sRGB step, so that is
// added to the tolerance.
void expectRedToBlue(const std::vector<float>& color) {
    for (int x : {2, 20, 32, 45, 61}) {
        const double u = acrossAt(x);
        const float* p = &color[(size_t(32) * kWidth + size_t(x)) * 4];
        for (size_t c = 0; c < 3; ++c) {
            double albedo = kRed[c] + (kBlue[c] - kRed[c]) * u;
            int code = int(std::lround(255.0 * srgbEncode(albedo)));
            double storageStep = srgb8Exact(std::min(code + 1, 255)) - srgb8Exact(code);
            double expected = albedo / kPi * kIrradiance;
            double tolerance = 0.01 * expected + smallFloatStep(float(expected), c == 2 ? 5 : 6) +
                               storageStep / kPi * kIrradiance;
            EXPECT_NEAR(p[c], expected, tolerance) << "pixel x " << x << " channel " << c;
        }
    }
}

TEST(DisplayColor, VertexColoursInterpolateBetweenPoints) {
    // Red on the left column, blue on the right, their mean in the middle.
    DisplayColorScene s;
    Rgb middle{};
    for (size_t c = 0; c < 3; ++c) middle[c] = 0.5f * (kRed[c] + kBlue[c]);
    s.addHalves({kRed, middle, kBlue, kRed, middle, kBlue}, OBSCURA_INTERPOLATION_VERTEX);
    expectRedToBlue(s.render());
}

TEST(DisplayColor, ConstantOpacityBelowOneIsTransparent) {
    // Over an empty (black, transparent) background: premultiplied colour opacity x lit, alpha opacity.
    DisplayColorScene s;
    const float opacity = 0.5f;
    s.addHalves({kRed}, OBSCURA_INTERPOLATION_CONSTANT, opacity);
    auto color = s.render();
    auto expected = lambert(kRed, opacity);
    const float* p = &color[(size_t(32) * kWidth + 16) * 4];
    const int mantissa[3] = {6, 6, 5};
    for (size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(p[c], expected[c], 0.01 * expected[c] + smallFloatStep(float(expected[c]), mantissa[c])) << c;
    EXPECT_NEAR(p[3], opacity, 1.0f / 255.0f);
}

// Opacity varying over the prim: premultiplied colour opacity x lit and alpha opacity where it is
// below 1, the plain lit colour (alpha 1) where it is 1.
void expectOver(const std::vector<float>& color, int x, int y, const Rgb& albedo, double opacity) {
    auto expected = lambert(albedo, opacity);
    const float* p = &color[(size_t(y) * kWidth + size_t(x)) * 4];
    const int mantissa[3] = {6, 6, 5};
    for (size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(p[c], expected[c], 0.01 * expected[c] + smallFloatStep(float(expected[c]), mantissa[c]))
            << "pixel (" << x << ", " << y << ") channel " << c;
    EXPECT_NEAR(p[3], opacity, 1.0f / 255.0f) << "pixel (" << x << ", " << y << ")";
}

HostValue floats(std::vector<float> values) {
    HostValue v;
    v.type = OBSCURA_VALUE_FLOAT;
    v.isArray = true;
    v.count = values.size();
    v.floats = std::move(values);
    return v;
}

TEST(DisplayColor, UniformOpacityMakesOneFaceTransparent) {
    DisplayColorScene s;
    s.addHalves({kRed}, OBSCURA_INTERPOLATION_CONSTANT);
    s.host.set("/Halves", "primvars:displayOpacity", floats({1.0f, 0.25f}));
    s.host.setInterpolation("/Halves", "primvars:displayOpacity", OBSCURA_INTERPOLATION_UNIFORM);
    s.host.api().markDirty(s.host.delegate(), "/Halves", OBSCURA_DIRTY_PRIMVAR);
    auto color = s.render();
    expectOver(color, 16, 32, kRed, 1.0);
    expectOver(color, 48, 32, kRed, 0.25);
}

TEST(DisplayColor, FaceVaryingOpacityFollowsEachFacesCorners) {
    DisplayColorScene s;
    s.addHalves({kBlue}, OBSCURA_INTERPOLATION_CONSTANT);
    s.host.set("/Halves", "primvars:displayOpacity", floats({0.5f, 0.5f, 0.5f, 0.5f, 1.0f, 1.0f, 1.0f, 1.0f}));
    s.host.setInterpolation("/Halves", "primvars:displayOpacity", OBSCURA_INTERPOLATION_FACE_VARYING);
    s.host.api().markDirty(s.host.delegate(), "/Halves", OBSCURA_DIRTY_PRIMVAR);
    auto color = s.render();
    expectOver(color, 16, 32, kBlue, 0.5);
    expectOver(color, 48, 32, kBlue, 1.0);
}

TEST(DisplayColor, VertexOpacityInterpolatesBetweenPoints) {
    // Opacity 0.2 on the left column, 1 on the right, 0.6 in the middle: affine in x.
    DisplayColorScene s;
    s.addHalves({kGreen}, OBSCURA_INTERPOLATION_CONSTANT);
    s.host.set("/Halves", "primvars:displayOpacity", floats({0.2f, 0.6f, 1.0f, 0.2f, 0.6f, 1.0f}));
    s.host.setInterpolation("/Halves", "primvars:displayOpacity", OBSCURA_INTERPOLATION_VERTEX);
    s.host.api().markDirty(s.host.delegate(), "/Halves", OBSCURA_DIRTY_PRIMVAR);
    auto color = s.render();
    for (int x : {4, 20, 40, 56}) expectOver(color, x, 32, kGreen, 0.2 + 0.8 * acrossAt(x));
}

// The halves (red) as the prototype of two instances, each squeezed to a panel of one side of the
// view: the left centred at pixel column 16, the right at 48.
void instanceHalves(DisplayColorScene& s, std::map<std::string, HostValue> primvars) {
    s.addHalves({kRed}, OBSCURA_INTERPOLATION_CONSTANT);
    std::map<std::string, HostValue> values{{"prototypes", HostValue::paths({"/Halves"})},
                                            {"protoIndices", HostValue::intArray({0, 0})},
                                            {"positions", HostValue::points({{-0.5f, 0, 0}, {0.5f, 0, 0}})},
                                            {"scales", HostValue::points({{0.4f, 0.8f, 1.0f}, {0.4f, 0.8f, 1.0f}})}};
    values.insert(primvars.begin(), primvars.end());
    s.host.addPrim("instancer", "/Instancer", values);
    for (const auto& [name, value] : primvars) s.host.setInterpolation("/Instancer", name, OBSCURA_INTERPOLATION_VERTEX);
}

TEST(DisplayColor, InstancerPrimvarsColourEachInstance) {
    DisplayColorScene s;
    instanceHalves(s, {{"primvars:displayColor", HostValue::points({kGreen, kBlue})}});
    auto color = s.render();
    expectRadiance(color, 16, 32, lambert(kGreen));
    expectRadiance(color, 48, 32, lambert(kBlue));
}

TEST(DisplayColor, InstancerOpacityMakesThoseInstancesTranslucent) {
    DisplayColorScene s;
    instanceHalves(s, {{"primvars:displayOpacity", floats({0.5f, 1.0f})}});
    auto color = s.render();
    expectOver(color, 16, 32, kRed, 0.5);  // the prototype's colour, the instance's opacity
    expectOver(color, 48, 32, kRed, 1.0);
}

TEST(DisplayColor, InstancerPrimvarOfAWrongCountIsIgnoredWithAWarning) {
    DisplayColorScene s;
    instanceHalves(s, {{"primvars:displayColor", HostValue::points({kGreen, kBlue, kGreen})}});
    auto color = s.render();
    expectRadiance(color, 16, 32, lambert(kRed));
    expectRadiance(color, 48, 32, lambert(kRed));
    bool warned = false;
    for (const std::string& w : s.host.loggedWarnings())
        warned |= w.find("/Instancer: primvars:displayColor has 3 elements but there are 2 instances; ignored") !=
                  std::string::npos;
    EXPECT_TRUE(warned);
}

// Points (sphere impostors) take displayOpacity like meshes: constant through the fallback
// material, per point through their vertices; below 1 they draw in the transparent pass, the near
// side of each sphere. Two red points of radius 0.3 at x = -0.5 and 0.5.
constexpr double kDotRadius = 0.3;
constexpr std::array<double, 2> kDotX{-0.5, 0.5};

void addDots(DisplayColorScene& s, const HostValue& opacity, ObscuraInterpolation interpolation) {
    s.host.addPrim("points", "/Dots",
                   {{"points", HostValue::points({{float(kDotX[0]), 0, 0}, {float(kDotX[1]), 0, 0}})},
                    {"widths", floats({float(2 * kDotRadius)})},
                    {"primvars:displayColor", HostValue::points({kRed})},
                    {"primvars:displayOpacity", opacity}});
    s.host.setInterpolation("/Dots", "widths", OBSCURA_INTERPOLATION_CONSTANT);
    s.host.setInterpolation("/Dots", "primvars:displayColor", OBSCURA_INTERPOLATION_CONSTANT);
    s.host.setInterpolation("/Dots", "primvars:displayOpacity", interpolation);
}

// Lambert at pixel (x, 31), on the near side of dot `dot` where that pixel's line of sight meets
// it (the light shines down -Z, so N.L is the normal's z), seen through `opacity`.
void expectDot(const std::vector<float>& color, size_t dot, double opacity) {
    const double tanHalf = kLitPlaneTanHalfFov, d = kLitPlaneCameraDistance;
    const int x = int(std::floor((kDotX[dot] / (d * tanHalf) + 1.0) / 2.0 * kWidth)), y = 31;
    const auto p = planePointAtPixel(x, y, d, tanHalf);
    // Eye (0, 0, d) towards p; o: the eye from the dot's centre.
    const std::array<double, 3> dir{p[0], p[1], -d}, o{-kDotX[dot], 0.0, d};
    const double a = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
    const double b = o[0] * dir[0] + o[1] * dir[1] + o[2] * dir[2];
    const double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - kDotRadius * kDotRadius;
    ASSERT_GT(b * b - a * c, 0.0) << "the pixel sees the dot";
    const double t = (-b - std::sqrt(b * b - a * c)) / a;
    const double facing = (o[2] + t * dir[2]) / kDotRadius;
    const float* px = &color[(size_t(y) * kWidth + size_t(x)) * 4];
    const int mantissa[3] = {6, 6, 5};
    for (size_t ch = 0; ch < 3; ++ch) {
        const double expected = kRed[ch] / kPi * kIrradiance * facing * opacity;
        EXPECT_NEAR(px[ch], expected, 0.01 * expected + smallFloatStep(float(expected), mantissa[ch]))
            << "dot " << dot << " channel " << ch;
    }
    EXPECT_NEAR(px[3], opacity, 1.0f / 255.0f) << "dot " << dot;
}

TEST(DisplayColor, ConstantOpacityMakesPointsTranslucent) {
    DisplayColorScene s;
    addDots(s, floats({0.5f}), OBSCURA_INTERPOLATION_CONSTANT);
    auto color = s.render();
    expectDot(color, 0, 0.5);
    expectDot(color, 1, 0.5);
    EXPECT_NEAR(color[(size_t(31) * kWidth + 32) * 4 + 3], 0.0f, 1e-6f) << "between them: neither sphere nor its cube";
    // Pixel (24, 23) sees the left dot's cube (its near face spans 0.319 either side of the centre
    // on the z = 0 plane) but passes 0.377 from the centre, outside the sphere (0.318 there).
    EXPECT_NEAR(color[(size_t(23) * kWidth + 24) * 4 + 3], 0.0f, 1e-6f) << "inside the cube, outside the sphere";
}

TEST(DisplayColor, PerPointOpacityMakesThosePointsTranslucent) {
    DisplayColorScene s;
    addDots(s, floats({0.25f, 1.0f}), OBSCURA_INTERPOLATION_VERTEX);
    auto color = s.render();
    expectDot(color, 0, 0.25);
    expectDot(color, 1, 1.0);
}

// BasisCurves take displayColor and displayOpacity as meshes do: a ribbon across the view (a
// linear curve along x, as wide as the view is tall, its normals facing the camera) is lit as the
// halves are, coloured along its length.
void addRibbon(DisplayColorScene& s, const std::vector<Rgb>& colours, ObscuraInterpolation interpolation) {
    s.host.addPrim("basisCurves", "/Ribbon",
                   {{"points", HostValue::points({{-kHalf, 0, 0}, {kHalf, 0, 0}})},
                    {"curveVertexCounts", HostValue::intArray({2})},
                    {"type", HostValue::token("linear")},
                    {"widths", floats({2 * kHalf})},
                    {"normals", HostValue::points({{0, 0, 1}})},
                    {"primvars:displayColor", HostValue::points(colours)}});
    s.host.setInterpolation("/Ribbon", "widths", OBSCURA_INTERPOLATION_CONSTANT);
    s.host.setInterpolation("/Ribbon", "normals", OBSCURA_INTERPOLATION_CONSTANT);
    s.host.setInterpolation("/Ribbon", "primvars:displayColor", interpolation);
}

TEST(DisplayColor, ConstantColoursACurve) {
    DisplayColorScene s;
    addRibbon(s, {kRed}, OBSCURA_INTERPOLATION_CONSTANT);
    auto color = s.render();
    for (auto [x, y] : {std::pair{8, 8}, {32, 32}, {56, 60}}) expectRadiance(color, x, y, lambert(kRed));
}

TEST(DisplayColor, VertexColoursInterpolateAlongACurve) {
    DisplayColorScene s;
    addRibbon(s, {kRed, kBlue}, OBSCURA_INTERPOLATION_VERTEX);
    expectRedToBlue(s.render());
}

TEST(DisplayColor, VertexOpacityInterpolatesAlongACurve) {
    DisplayColorScene s;
    addRibbon(s, {kGreen}, OBSCURA_INTERPOLATION_CONSTANT);
    s.host.set("/Ribbon", "primvars:displayOpacity", floats({0.2f, 1.0f}));
    s.host.setInterpolation("/Ribbon", "primvars:displayOpacity", OBSCURA_INTERPOLATION_VERTEX);
    s.host.api().markDirty(s.host.delegate(), "/Ribbon", OBSCURA_DIRTY_PRIMVAR);
    auto color = s.render();
    for (int x : {4, 20, 40, 56}) expectOver(color, x, 32, kGreen, 0.2 + 0.8 * acrossAt(x));
}

}  // namespace
}  // namespace obscura::test
