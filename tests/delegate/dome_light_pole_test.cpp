// UsdLuxDomeLight_1 through the harness's scene host: its `poleAxis` turns the dome's top pole to
// the stage's up axis ("scene", the fallback), +Y or +Z; UsdLuxDomeLight's pole is +Y whatever the
// stage's up axis. The check is physical: a sky (radiance 1 above the dome's horizon, 0 below)
// gives a plane facing the pole an irradiance of pi and a plane facing the horizon pi / 2 (the
// tilted plane's E = pi L (1 + cos t) / 2, exact through the dome's spherical harmonics;
// dome_texture_test.cpp), so a plane facing +Z is twice as bright under a +Z pole as under +Y.
#include "harness/image/exr_writer.h"
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

namespace obscura::test {
namespace {

// A latlong map (+Y up, OpenEXR's layout): its upper half, latitudes above 0, radiance 1.
std::string writeSky(const std::filesystem::path& dir) {
    constexpr int width = 64, height = 32;
    std::vector<float> rgba;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float l = y < height / 2 ? 1.0f : 0.0f;
            rgba.insert(rgba.end(), {l, l, l, 1.0f});
        }
    std::string path = (dir / "sky.exr").string();
    image::ExrLayer layer{"", {"R", "G", "B", "A"}, image::ExrLayer::PixelType::Float, rgba.data(),
                          size_t(width) * 4 * sizeof(float)};
    auto written = image::writeExr(path, width, height, {layer});
    EXPECT_FALSE(image::isError(written)) << image::errorOf(written);
    return path;
}

class DomeLightPole : public ::testing::Test {
protected:
    DomeLightPole() {
        dir_ = std::filesystem::temp_directory_path() / ("obscura_dome_pole_" + std::to_string(getpid()));
        std::filesystem::create_directories(dir_);
        sky_ = writeSky(dir_);
    }
    ~DomeLightPole() override { std::filesystem::remove_all(dir_); }

    // The centre pixel's red channel: a plane facing +Z (the camera) under the dome `domeType`
    // with `poleAxis` (none authored when empty) on a stage whose up axis is `upAxis`; `warned`
    // counts the host's messages about the poleAxis.
    float planeUnder(const std::string& upAxis, const std::string& domeType, const std::string& poleAxis,
                     size_t* warned = nullptr) {
        std::string text = "#usda 1.0\n(\n    upAxis = \"" + upAxis + "\"\n)\n" + usdaCamera() + R"(
def Mesh "Ground"
{
    point3f[] points = [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
}
def )" + domeType + R"( "Sky"
{
    asset inputs:texture:file = @)" + sky_ + R"(@
    float inputs:specular = 0
)" + (poleAxis.empty() ? "" : "    uniform token poleAxis = \"" + poleAxis + "\"\n") + "}\n";
        HostedStage hosted(usda::Stage::openFromString(text, "dome_pole.usda"));
        std::vector<float> color = hosted.renderAov("color", 4);
        EXPECT_EQ(hosted.lastStatus, OBSCURA_OK);
        EXPECT_EQ(hosted.messagesWith("not supported"), 0u);
        if (warned) *warned = hosted.messagesWith("poleAxis");
        return color[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 4];
    }

    std::filesystem::path dir_;
    std::string sky_;
};

TEST_F(DomeLightPole, AZPoleLightsAnUpwardPlaneTwiceAsMuchAsTheYPole) {
    float zPole = planeUnder("Y", "DomeLight_1", "Z");
    float yPole = planeUnder("Y", "DomeLight_1", "Y");
    ASSERT_GT(yPole, 0.01f);
    EXPECT_NEAR(zPole / yPole, 2.0f, 0.06f) << zPole << " " << yPole;
}

TEST_F(DomeLightPole, TheFallbackFollowsTheStageUpAxis) {
    EXPECT_EQ(planeUnder("Z", "DomeLight_1", ""), planeUnder("Y", "DomeLight_1", "Z"));
    EXPECT_EQ(planeUnder("Y", "DomeLight_1", ""), planeUnder("Z", "DomeLight_1", "Y"));
}

// A token outside scene, Y and Z is reported with the prim and taken as "scene".
TEST_F(DomeLightPole, AnUnknownPoleAxisIsReportedAndTheStageUpAxisTaken) {
    size_t warned = 0;
    EXPECT_EQ(planeUnder("Z", "DomeLight_1", "X", &warned), planeUnder("Z", "DomeLight_1", "Z"));
    EXPECT_EQ(warned, 1u);
}

TEST_F(DomeLightPole, TheOriginalDomeLightKeepsItsPoleAlongY) {
    EXPECT_EQ(planeUnder("Z", "DomeLight", ""), planeUnder("Z", "DomeLight_1", "Y"));
}

}  // namespace
}  // namespace obscura::test
