// A USD stage's PortalLight (UsdLux: a rectangle that "guides sampling of a dome light") is a
// sampler's hint: the dome lights the scene as without it, and the host reports nothing.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace obscura::test {
namespace {

std::string domeLitPlane(const std::string& extra) {
    return "#usda 1.0\n" + usdaCamera() + R"(
def Mesh "Ground"
{
    point3f[] points = [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
}
def DomeLight "Sky"
{
    float inputs:intensity = 2
}
)" + extra;
}

TEST(PortalLight, TheDomeLightsAsWithoutItAndNothingIsReported) {
    HostedStage without(usda::Stage::openFromString(domeLitPlane(""), "dome.usda"));
    HostedStage with(usda::Stage::openFromString(domeLitPlane(R"(def PortalLight "Window"
{
    float inputs:width = 1
    float inputs:height = 1
    double3 xformOp:translate = (0, 0, 1)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
)"),
                                                 "portal.usda"));
    std::vector<float> a = without.renderAov("color", 4), b = with.renderAov("color", 4);
    EXPECT_EQ(with.lastStatus, OBSCURA_OK);
    EXPECT_TRUE(with.host->messages().empty()) << with.host->messages().front().text;
    ASSERT_EQ(a.size(), b.size());
    EXPECT_GT(a[(32 * kWidth + 32) * 4], 0.1f);  // lit
    EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace obscura::test
