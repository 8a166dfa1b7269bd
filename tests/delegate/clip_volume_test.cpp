// Clip volumes (seed 004): a light clipped to a closed mesh lights only surfaces inside it. With
// shadows off, a bulb in one room lights the next room's floor through the wall; clipped to its
// room, it stops at the wall. The volume may be concave or in pieces (parity in stencil), and a
// clip volume that cannot be used is reported while the light still renders.
#include "harness/usd_scene_host.h"
#include "tests/delegate/render_fixture.h"

namespace obscura::test {
namespace {

// Closed boxes as one mesh (outward quads), hidden: drawn only into the stencil.
void addBoxes(TestHost& host, const std::string& path, const std::vector<std::pair<std::array<float, 3>, std::array<float, 3>>>& boxes) {
    std::vector<std::array<float, 3>> points;
    std::vector<int32_t> counts, indices;
    for (const auto& [lo, hi] : boxes) {
        int32_t base = int32_t(points.size());
        for (int i = 0; i < 8; ++i)
            points.push_back({(i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]});
        const int32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& f : faces) {
            counts.push_back(4);
            for (int32_t v : f) indices.push_back(base + v);
        }
    }
    host.addPrim("mesh", path,
                 {{"points", HostValue::points(points)},
                  {"faceVertexCounts", HostValue::intArray(counts)},
                  {"faceVertexIndices", HostValue::intArray(indices)},
                  {"subdivisionScheme", HostValue::token("none")},
                  {"visibility", HostValue::token("invisible")}});
}

void setShadows(TestHost& host, bool on) {
    int32_t flag = on ? 1 : 0;
    ObscuraValue v{OBSCURA_VALUE_BOOL, 0, 1, &flag};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "shadows", &v), OBSCURA_OK);
}

constexpr double kBulbRadiance = 400.0, kBulbRadius = 0.1;

// The analytic Lambert radiance of the floor under the bulb at `bulb`.
double floorRadiance(int x, int y, std::array<double, 3> bulb) {
    auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
    double dx = p[0] - bulb[0], dy = p[1] - bulb[1], d2 = dx * dx + dy * dy + bulb[2] * bulb[2];
    return kLitPlaneAlbedo / kPi * kPi * kBulbRadiance * kBulbRadius * kBulbRadius / d2 * (bulb[2] / std::sqrt(d2));
}

void addBulb(TestHost& host, std::array<double, 3> at, const std::string& clip) {
    std::map<std::string, HostValue> values = {{"inputs:intensity", HostValue::floatValue(float(kBulbRadiance))},
                                               {"inputs:radius", HostValue::floatValue(float(kBulbRadius))},
                                               {"inputs:specular", HostValue::floatValue(0.0f)}};
    if (!clip.empty()) values["obscura:clipVolume"] = HostValue::path(clip);
    host.addPrim("sphereLight", "/Bulb", values, translation(at[0], at[1], at[2]));
}

// The floor spans x in [-1.05, 1.05] in view; a wall 2 units high stands at x = 0 (seen edge on).
// The bulb hangs in the left room, high enough that no pixel sees it at a grazing angle (where the
// 8-bit best-fit normal's 0.3 degrees would show). `msaa`: the G-buffer's samples per pixel (the
// volumes then clip the resolved G-buffer's stencil, beside the MSAA edge bit).
void expectLightStopsAtTheWall(int32_t msaa) {
    const std::array<double, 3> bulb{-0.5, 0.0, 1.5};
    auto render = [&](bool clipped) {
        LitPlaneScene s;
        setShadows(s.host, false);
        ObscuraValue samples{OBSCURA_VALUE_INT, 0, 1, &msaa};
        EXPECT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "msaa", &samples), OBSCURA_OK);
        Matrix wall = lightPointingAlong({1, 0, 0});  // a plane turned to face +X, standing at x = 0
        wall[12] = 0, wall[13] = 0, wall[14] = 0;
        addPlane(s.host, "/Wall", "/Looks/Grey", 2.0, wall);
        addBoxes(s.host, "/LeftRoom", {{{-5.0f, -5.0f, -1.0f}, {-0.02f, 5.0f, 2.5f}}});
        addBulb(s.host, bulb, clipped ? "/LeftRoom" : "");
        return s.renderColor();
    };
    auto bleeding = render(false), clipped = render(true);
    const int leftColumn = 12, rightColumn = 52;  // x = -0.66 and x = +0.69 on the floor
    for (int y : {10, 32, 54}) {
        double left = floorRadiance(leftColumn, y, bulb), right = floorRadiance(rightColumn, y, bulb);
        float unclippedRight = bleeding[(size_t(y) * kWidth + rightColumn) * 4];
        EXPECT_NEAR(unclippedRight, right, 0.01 * right + smallFloatStep(float(right), 6)) << "unclipped light bleeds";
        expectRadiance(clipped, leftColumn, y, {left, left, left});
        expectRadiance(clipped, rightColumn, y, {0, 0, 0});
    }
}

TEST(ClipVolume, LightStopsAtTheWall) { expectLightStopsAtTheWall(1); }

TEST(ClipVolume, LightStopsAtTheWallWithFourSamples) { expectLightStopsAtTheWall(4); }

TEST(ClipVolume, AVolumeInPiecesAndConcaveRegionsClipsByParity) {
    // Two boxes meeting at an edge form an L over the floor; the bulb lights the L and not the
    // notch between its arms.
    LitPlaneScene s;
    setShadows(s.host, false);
    addBoxes(s.host, "/L", {{{-2.0f, -2.0f, -1.0f}, {0.0f, 2.0f, 2.0f}}, {{0.0f, -2.0f, -1.0f}, {2.0f, 0.0f, 2.0f}}});
    const std::array<double, 3> bulb{0.0, 0.0, 0.8};
    addBulb(s.host, bulb, "/L");
    auto color = s.renderColor();
    // Pixel rows grow downwards: row 12 is y = +0.63, row 52 is y = -0.63.
    const std::pair<int, int> inside[] = {{12, 12}, {12, 52}, {52, 52}}, notch[] = {{52, 12}, {40, 20}};
    for (auto [x, y] : inside) {
        double l = floorRadiance(x, y, bulb);
        expectRadiance(color, x, y, {l, l, l});
    }
    for (auto [x, y] : notch) expectRadiance(color, x, y, {0, 0, 0});
}

TEST(ClipVolume, AVolumeThatIsNotAMeshIsReportedAndTheLightStillShines) {
    LitPlaneScene s;
    const std::array<double, 3> bulb{0.0, 0.0, 0.8};
    addBulb(s.host, bulb, "/Looks/Grey");
    EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << s.host.lastError();
    auto color = s.host.readFloats("/Buffers/color");
    double l = floorRadiance(32, 32, bulb);
    expectRadiance(color, 32, 32, {l, l, l});
    bool reported = false;
    for (const auto& w : s.host.loggedWarnings()) reported = reported || w.find("/Looks/Grey is not a mesh") != std::string::npos;
    EXPECT_TRUE(reported);
}

TEST(ClipVolume, UsdaHostServesTheRelationship) {
    auto opened = usda::Stage::openFromString(R"(#usda 1.0
def SphereLight "Bulb"
{
    rel obscura:clipVolume = </Room>
}
def Mesh "Room"
{
}
)",
                                              "inline.usda");
    ASSERT_TRUE(std::holds_alternative<std::unique_ptr<usda::Stage>>(opened));
    harness::UsdSceneHost host(*std::get<std::unique_ptr<usda::Stage>>(opened));
    const ObscuraSceneDelegate& sd = host.sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/Bulb", "obscura:clipVolume", 0.0, &value), OBSCURA_OK);
    ASSERT_EQ(value.type, OBSCURA_VALUE_PATH);
    EXPECT_STREQ(static_cast<const char* const*>(value.data)[0], "/Room");
    EXPECT_NE(sd.getValue(sd.userData, "/Room", "obscura:clipVolume", 0.0, &value), OBSCURA_OK);
}

}  // namespace
}  // namespace obscura::test
