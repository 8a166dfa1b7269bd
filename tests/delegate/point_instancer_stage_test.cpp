// PointInstancers through the harness, as USD files author them: displayColor of vertex
// interpolation, indexed, colours each instance of a prototype mesh that has no material in place
// of the mesh's own (Hydra's instance primvars); a PointInstancer in another's prototype places
// its prototypes within each of the other's instances.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

namespace obscura::test {
namespace {

// Two instances of a red quad, squeezed to panels centred at x = -0.5 and 0.5 (pixel columns 16
// and 48 of the delegate tests' view), with the instancer's `primvars` lines.
std::string instancedQuads(const std::string& primvars) {
    return "#usda 1.0\n" + usdaCamera() +
           "def PointInstancer \"Instancer\"\n{\n"
           "    rel prototypes = [</Instancer/Prototypes/Quad>]\n"
           "    int[] protoIndices = [0, 0]\n"
           "    point3f[] positions = [(-0.5, 0, 0), (0.5, 0, 0)]\n"
           "    float3[] scales = [(0.4, 0.8, 1), (0.4, 0.8, 1)]\n" +
           primvars +
           "    def Scope \"Prototypes\"\n    {\n"
           "        def Mesh \"Quad\"\n        {\n"
           "            point3f[] points = [(-1.2, -1.2, 0), (1.2, -1.2, 0), (1.2, 1.2, 0), (-1.2, 1.2, 0)]\n"
           "            int[] faceVertexCounts = [4]\n            int[] faceVertexIndices = [0, 1, 2, 3]\n"
           "            color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n"
           "        }\n    }\n}\n";
}

using Rgb = std::array<float, 3>;

void expectPanels(const std::vector<float>& albedo, const Rgb& left, const Rgb& right) {
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    for (auto [x, expected] : {std::pair{16, left}, {48, right}})
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(albedo[(size_t(32) * kWidth + size_t(x)) * 3 + c], expected[c], 0.02f) << "x " << x << " channel " << c;
}

TEST(PointInstancerStage, IndexedDisplayColorColoursEachInstance) {
    HostedStage scene(usda::Stage::openFromString(
        instancedQuads("    color3f[] primvars:displayColor = [(0.05, 0.8, 0.05), (0.05, 0.05, 0.8)] (\n"
                       "        interpolation = \"vertex\"\n    )\n"
                       "    int[] primvars:displayColor:indices = [1, 0]\n"),
        "instances.usda"));
    expectPanels(scene.renderAlbedo(), {0.05f, 0.05f, 0.8f}, {0.05f, 0.8f, 0.05f});
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

TEST(PointInstancerStage, WithoutThemThePrototypesOwnColourShows) {
    HostedStage scene(usda::Stage::openFromString(instancedQuads(""), "instances.usda"));
    expectPanels(scene.renderAlbedo(), {0.8f, 0.05f, 0.05f}, {0.8f, 0.05f, 0.05f});
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

// Rows of two quads (x = -0.5 and 0.5, each 0.4 wide) inside the prototype of an instancer of two
// rows (y = -0.5 and 0.5): the quads' centres at pixel columns 16 and 48 (the delegate tests' view,
// x = -0.5, 0.5) and rows 48 and 16. The inner instancer and the quad carry transforms of their
// own, relative to their prototypes.
TEST(PointInstancerStage, NestedInstancersPlaceEveryCombination) {
    const std::string text =
        "#usda 1.0\n" + usdaCamera() +
        "def PointInstancer \"Rows\"\n{\n"
        "    rel prototypes = [</Rows/Prototypes/Row>]\n"
        "    int[] protoIndices = [0, 0]\n"
        "    point3f[] positions = [(0, -0.7, 0), (0, 0.3, 0)]\n"
        "    def Scope \"Prototypes\"\n    {\n"
        "        def PointInstancer \"Row\"\n        {\n"
        "            double3 xformOp:translate = (0, 0.2, 0)\n"
        "            uniform token[] xformOpOrder = [\"xformOp:translate\"]\n"
        "            rel prototypes = [</Rows/Prototypes/Row/Prototypes/Quad>]\n"
        "            int[] protoIndices = [0, 0]\n"
        "            point3f[] positions = [(-0.6, 0, 0), (0.4, 0, 0)]\n"
        "            def Scope \"Prototypes\"\n            {\n"
        "                def Mesh \"Quad\"\n                {\n"
        "                    double3 xformOp:translate = (0.1, 0, 0)\n"
        "                    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n"
        "                    point3f[] points = [(-0.2, -0.2, 0), (0.2, -0.2, 0), (0.2, 0.2, 0), (-0.2, 0.2, 0)]\n"
        "                    int[] faceVertexCounts = [4]\n                    int[] faceVertexIndices = [0, 1, 2, 3]\n"
        "                }\n            }\n        }\n    }\n}\n";
    HostedStage scene(usda::Stage::openFromString(text, "nested.usda"));
    const std::vector<float> ids = scene.renderAov("primId", 1);
    ASSERT_EQ(ids.size(), size_t(kWidth) * kHeight);
    const float quad = ids[size_t(16) * kWidth + 16];
    EXPECT_GE(quad, 0.0f) << "a quad at the top left";
    for (auto [x, y] : {std::pair{16, 16}, {48, 16}, {16, 48}, {48, 48}})
        EXPECT_EQ(ids[size_t(y) * kWidth + size_t(x)], quad) << "a quad centred at pixel " << x << ", " << y;
    // Each quad is 0.4 wide: 12 pixels (0.4 / 2.0955 x 64 = 12.2) around its centre, none between.
    EXPECT_LT(ids[size_t(16) * kWidth + 32], 0.0f);
    EXPECT_LT(ids[size_t(32) * kWidth + 16], 0.0f);
    EXPECT_EQ(std::count(ids.begin(), ids.end(), quad), 4 * 12 * 12);
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

}  // namespace
}  // namespace obscura::test
