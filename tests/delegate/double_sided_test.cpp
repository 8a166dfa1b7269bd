// doubleSided (UsdGeomGprim): a single-sided surface seen from behind is not drawn, a double-sided
// one is, facing the viewer. A square that fills the view of a camera at (0, 0, 5) looking down -Z
// turns its back to the camera; a distant light shines down -Z, so a drawn back is lit head-on
// (Lambert displayColor / pi * E) and an undrawn one leaves the empty background (black,
// transparent). A Mesh is single-sided unless it says otherwise; a Plane is double-sided unless it
// says otherwise (UsdGeomPlane's fallback).
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <optional>

namespace obscura::test {
namespace {

constexpr double kIrradiance = 3.0;
const std::array<float, 3> kRed{srgb8Exact(200), srgb8Exact(40), srgb8Exact(40)};
constexpr float kHalf = 1.2f;  // beyond the view's half-size at z = 0 (1.04775)
// Half a turn about Y: a surface facing +Z faces -Z, away from the camera (the winding kept).
const Matrix kTurnedAround{-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1};

struct BackViewScene {
    TestHost host;
    BackViewScene() {
        addLitPlaneViewAndSun(host, kIrradiance);
    }
    // A red square at z = 0, its front facing the camera or away from it: a mesh wound
    // counter-clockwise or clockwise seen from the camera.
    void addMesh(bool facingAway, std::optional<bool> doubleSided) {
        std::map<std::string, HostValue> values{
            {"points",
             HostValue::points({{-kHalf, -kHalf, 0}, {kHalf, -kHalf, 0}, {kHalf, kHalf, 0}, {-kHalf, kHalf, 0}})},
            {"faceVertexCounts", HostValue::intArray({4})},
            {"faceVertexIndices", HostValue::intArray(facingAway ? std::vector<int32_t>{0, 3, 2, 1}
                                                                 : std::vector<int32_t>{0, 1, 2, 3})},
            {"subdivisionScheme", HostValue::token("none")}};
        addSquare("mesh", values, doubleSided, identity());
    }
    // A red Plane (its normal along +Z), turned to face away from the camera or not.
    void addPlane(bool facingAway, std::optional<bool> doubleSided) {
        const HostValue side = HostValue::doubleValue(2 * kHalf);
        addSquare("plane", {{"width", side}, {"length", side}}, doubleSided, facingAway ? kTurnedAround : identity());
    }
    void addSquare(const std::string& type, std::map<std::string, HostValue> values, std::optional<bool> doubleSided,
                   const Matrix& transform) {
        values["primvars:displayColor"] = HostValue::points({kRed});
        if (doubleSided) values["doubleSided"] = HostValue::boolean(*doubleSided);
        host.addPrim(type, "/Square", values, transform);
        host.setInterpolation("/Square", "primvars:displayColor", OBSCURA_INTERPOLATION_CONSTANT);
    }
    std::vector<float> render() {
        EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
        return host.readFloats("/Buffers/color");
    }
};

constexpr std::array<std::pair<int, int>, 3> kPixels{{{8, 8}, {32, 32}, {56, 60}}};

// The back drawn, facing the viewer: lit head-on, opaque.
void expectDrawn(const std::vector<float>& color) {
    for (auto [x, y] : kPixels) {
        expectRadiance(color, x, y,
                       {kRed[0] / kPi * kIrradiance, kRed[1] / kPi * kIrradiance, kRed[2] / kPi * kIrradiance});
        EXPECT_EQ(color[(size_t(y) * kWidth + size_t(x)) * 4 + 3], 1.0f) << "pixel (" << x << ", " << y << ")";
    }
}

// Nothing drawn: the empty background.
void expectEmpty(const std::vector<float>& color) {
    for (auto [x, y] : kPixels)
        for (size_t c = 0; c < 4; ++c)
            EXPECT_EQ(color[(size_t(y) * kWidth + size_t(x)) * 4 + c], 0.0f)
                << "pixel (" << x << ", " << y << ") channel " << c;
}

// What a surface facing away from the camera shows: drawn or empty.
template <class Add>
void expectFromBehind(Add add, std::optional<bool> doubleSided, bool drawn) {
    SCOPED_TRACE(doubleSided ? (*doubleSided ? "doubleSided = true" : "doubleSided = false")
                             : "doubleSided not authored");
    BackViewScene s;
    add(s, true, doubleSided);
    if (drawn) expectDrawn(s.render());
    else expectEmpty(s.render());
}

TEST(DoubleSided, AMeshSeenFromBehindIsDrawnOnlyWhenDoubleSided) {
    auto mesh = [](BackViewScene& s, bool facingAway, std::optional<bool> d) { s.addMesh(facingAway, d); };
    expectFromBehind(mesh, std::nullopt, false);
    expectFromBehind(mesh, false, false);
    expectFromBehind(mesh, true, true);
}

TEST(DoubleSided, APlaneSeenFromBehindIsDrawnUnlessItIsSingleSided) {
    auto plane = [](BackViewScene& s, bool facingAway, std::optional<bool> d) { s.addPlane(facingAway, d); };
    expectFromBehind(plane, std::nullopt, true);
    expectFromBehind(plane, true, true);
    expectFromBehind(plane, false, false);
}

// Facing the camera, single-sided surfaces are drawn: only backs are culled.
TEST(DoubleSided, ASingleSidedSurfaceFacingTheCameraIsDrawn) {
    BackViewScene mesh;
    mesh.addMesh(false, false);
    expectDrawn(mesh.render());
    BackViewScene plane;
    plane.addPlane(false, false);
    expectDrawn(plane.render());
}

}  // namespace
}  // namespace obscura::test
