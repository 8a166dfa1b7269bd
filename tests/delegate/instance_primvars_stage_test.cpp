// A PointInstancer's primvars through the harness, as a USD file authors them: displayColor of
// vertex interpolation, indexed, colours each instance of a prototype mesh that has no material in
// place of the mesh's own (Hydra's instance primvars).
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

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

TEST(InstancePrimvarsStage, IndexedDisplayColorColoursEachInstance) {
    HostedStage scene(usda::Stage::openFromString(
        instancedQuads("    color3f[] primvars:displayColor = [(0.05, 0.8, 0.05), (0.05, 0.05, 0.8)] (\n"
                       "        interpolation = \"vertex\"\n    )\n"
                       "    int[] primvars:displayColor:indices = [1, 0]\n"),
        "instances.usda"));
    expectPanels(scene.renderAlbedo(), {0.05f, 0.05f, 0.8f}, {0.05f, 0.8f, 0.05f});
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

TEST(InstancePrimvarsStage, WithoutThemThePrototypesOwnColourShows) {
    HostedStage scene(usda::Stage::openFromString(instancedQuads(""), "instances.usda"));
    expectPanels(scene.renderAlbedo(), {0.8f, 0.05f, 0.05f}, {0.8f, 0.05f, 0.05f});
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

}  // namespace
}  // namespace obscura::test
