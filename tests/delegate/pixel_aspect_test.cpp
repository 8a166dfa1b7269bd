// The render setting pixelAspectRatio (UsdRenderSettings' pixelAspectRatio): the camera's aperture
// is conformed to an image width x ratio wide. A camera at z = 5 with a square 20.955 mm aperture
// and a 50 mm lens sees [-1.04775, 1.04775]^2 at z = 0 in a square image of square pixels; with
// pixels twice as wide as high the image is twice as wide as high, so the view widens to
// +-2.0955 across the same 64 pixels and a quad over x in [0, 1.2] ends at pixel column
// 32 + 32 x 1.2 / 2.0955 = 50.3 instead of covering the right half.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

const std::string kStage = "#usda 1.0\n" + usdaCamera() + R"(def Mesh "Quad"
{
    point3f[] points = [(0, 0, 0), (1.2, 0, 0), (1.2, 1.2, 0), (0, 1.2, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    uniform token subdivisionScheme = "none"
}
)";

TEST(PixelAspectRatio, WidensTheViewByTheRatio) {
    HostedStage scene(usda::Stage::openFromString(kStage, "pixel_aspect.usda"));
    auto drawn = [&](const std::vector<float>& ids, int x) { return ids.at(size_t(16) * kWidth + size_t(x)) >= 0.0f; };
    auto square = scene.renderAov("primId", 1);
    EXPECT_TRUE(drawn(square, 40));
    EXPECT_TRUE(drawn(square, 60));
    float ratio = 2.0f;
    ObscuraValue value{OBSCURA_VALUE_FLOAT, 0, 1, &ratio};
    ASSERT_EQ(scene.api().setRenderSetting(scene.delegate, "pixelAspectRatio", &value), OBSCURA_OK);
    auto wide = scene.renderAov("primId", 1);
    EXPECT_TRUE(drawn(wide, 33));
    EXPECT_TRUE(drawn(wide, 49));
    EXPECT_FALSE(drawn(wide, 52));
    EXPECT_FALSE(drawn(wide, 60));
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

}  // namespace
}  // namespace obscura::test
