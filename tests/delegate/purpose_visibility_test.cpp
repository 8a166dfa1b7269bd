// UsdGeomImageable's computed purpose and visibility as the harness's scene host answers them and
// the plugin draws them: purposes against the render setting includedPurposes (Hydra's render
// tags, default "default,render"), visibility inherited from a time-sampled ancestor, inactive
// prims left out. A camera at z = 5 whose view fills [-1.04775, 1.04775]^2 at z = 0 looks at one
// quad per quadrant; the primId AOV says which are drawn.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <string>

namespace obscura::test {
namespace {

// A quad covering the quadrant whose centre is (x, y) * 0.52 (x, y = +-1) at depth z, with extra
// attribute lines.
std::string quad(const std::string& name, int x, int y, const std::string& extra = "", double z = 0.0) {
    auto p = [&](double px, double py) {
        return "(" + std::to_string(px) + ", " + std::to_string(py) + ", " + std::to_string(z) + ")";
    };
    double x0 = x < 0 ? -1.2 : 0.0, x1 = x < 0 ? 0.0 : 1.2, y0 = y < 0 ? -1.2 : 0.0, y1 = y < 0 ? 0.0 : 1.2;
    return "def Mesh \"" + name + "\"\n{\n    point3f[] points = [" + p(x0, y0) + ", " + p(x1, y0) + ", " + p(x1, y1) +
           ", " + p(x0, y1) +
           "]\n    int[] faceVertexCounts = [4]\n    int[] faceVertexIndices = [0, 1, 2, 3]\n"
           "    uniform token subdivisionScheme = \"none\"\n" +
           extra + "\n}\n";
}

// Whether a prim is drawn at the centre of each quadrant: top left, top right, bottom left, bottom right.
std::array<bool, 4> drawnQuadrants(HostedStage& scene, double time = 0.0) {
    std::vector<float> ids = scene.renderAov("primId", 1, time);
    EXPECT_EQ(ids.size(), size_t(kWidth) * kHeight);
    if (ids.size() != size_t(kWidth) * kHeight) return {};
    auto at = [&](int px, int py) { return ids[size_t(py) * kWidth + size_t(px)] >= 0.0f; };
    return {at(16, 16), at(48, 16), at(16, 48), at(48, 48)};
}

std::string purposeStage() {
    return std::string("#usda 1.0\n") + usdaCamera() +
           quad("Default", -1, 1) +
           "def Xform \"RenderGroup\" { uniform token purpose = \"render\"\n" + quad("Child", 1, 1) + "}\n" +
           "def Xform \"ProxyGroup\" { uniform token purpose = \"proxy\"\n" + quad("Child", -1, -1) + "}\n" +
           // The child's own opinion wins over the guide it sits under (UsdGeomImageable::ComputePurpose).
           "def Xform \"GuideGroup\" { uniform token purpose = \"guide\"\n" +
           quad("Guide", 1, -1, "", 0.0) + quad("OwnDefault", 1, -1, "uniform token purpose = \"default\"", -0.5) + "}\n" +
           // Inactive: it would cover every quadrant in front of the others.
           "def Mesh \"Inactive\" ( active = false )\n{\n    point3f[] points = [(-2, -2, 1), (2, -2, 1), (2, 2, 1), (-2, 2, 1)]\n"
           "    int[] faceVertexCounts = [4]\n    int[] faceVertexIndices = [0, 1, 2, 3]\n}\n";
}

TEST(Purpose, DefaultAndRenderAreDrawnByDefault) {
    HostedStage scene(usda::Stage::openFromString(purposeStage(), "purpose.usda"));
    // Bottom right: the guide is left out, but the mesh behind it with its own default purpose is drawn.
    EXPECT_EQ(drawnQuadrants(scene), (std::array<bool, 4>{true, true, false, true}));
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

TEST(Purpose, IncludedPurposesChoosesWhatIsDrawn) {
    HostedStage scene(usda::Stage::openFromString(purposeStage(), "purpose.usda"));
    scene.setToken("includedPurposes", "proxy");
    EXPECT_EQ(drawnQuadrants(scene), (std::array<bool, 4>{false, false, true, false}));
    scene.setToken("includedPurposes", "guide,render");
    EXPECT_EQ(drawnQuadrants(scene), (std::array<bool, 4>{false, true, false, true}));
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

TEST(Purpose, AnUnknownPurposeInTheSettingIsRefused) {
    HostedStage scene(usda::Stage::openFromString(purposeStage(), "purpose.usda"));
    const char* text = "default,preview";
    ObscuraValue value{OBSCURA_VALUE_TOKEN, 0, 1, &text};
    EXPECT_EQ(scene.api().setRenderSetting(scene.delegate, "includedPurposes", &value), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(scene.api().lastError(scene.delegate)).find("'preview'"), std::string::npos)
        << scene.api().lastError(scene.delegate);
}

TEST(Purpose, BadPurposeDataIsReportedAndTheRestDraws) {
    // A purpose of the wrong type: the host warns where it is authored and the prim draws as default;
    // a token outside the schema's: the plugin skips that prim alone.
    std::string text = std::string("#usda 1.0\n") + usdaCamera() + quad("WrongType", -1, 1, "uniform float purpose = 1") +
                       quad("Unknown", 1, 1, "uniform token purpose = \"preview\"") + quad("Fine", -1, -1);
    HostedStage scene(usda::Stage::openFromString(text, "bad_purpose.usda"));
    scene.expectError("skipped prim /Unknown: purpose");
    EXPECT_EQ(drawnQuadrants(scene), (std::array<bool, 4>{true, false, true, false}));
    bool located = false;
    for (const auto& m : scene.host->messages())
        located |= m.text.find("/WrongType: purpose is authored as uniform float") != std::string::npos &&
                   m.where.file == "bad_purpose.usda" && m.where.line > 0;
    EXPECT_TRUE(located) << "no located warning for /WrongType";
    bool reported = false;
    for (const auto& e : scene.errors) reported |= e.find("/Unknown") != std::string::npos;
    EXPECT_TRUE(reported) << "the plugin did not report /Unknown's purpose";
}

TEST(Visibility, AnAnimatedAncestorResyncsItsChildrenEachFrame) {
    // The parent turns invisible at time 1 and visible again at 2; the children author nothing.
    std::string text = std::string("#usda 1.0\n") + usdaCamera() +
                       "def Xform \"Blink\" { token visibility.timeSamples = { 0: \"inherited\", 1: \"invisible\", 2: "
                       "\"inherited\" }\n" +
                       quad("Child", -1, 1) + "def Xform \"Deeper\" {\n" + quad("Grandchild", 1, 1) + "}\n}\n" +
                       quad("Steady", -1, -1) + "def Xform \"Hidden\" { token visibility = \"invisible\"\n" +
                       quad("Child", 1, -1, "token visibility = \"inherited\"") + "}\n";
    HostedStage scene(usda::Stage::openFromString(text, "blink.usda"));
    EXPECT_EQ(drawnQuadrants(scene, 0.0), (std::array<bool, 4>{true, true, true, false}));
    ASSERT_EQ(scene.host->markTimeVarying(scene.api(), scene.delegate), OBSCURA_OK);
    EXPECT_EQ(drawnQuadrants(scene, 1.0), (std::array<bool, 4>{false, false, true, false}));
    ASSERT_EQ(scene.host->markTimeVarying(scene.api(), scene.delegate), OBSCURA_OK);
    EXPECT_EQ(drawnQuadrants(scene, 2.0), (std::array<bool, 4>{true, true, true, false}));
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

}  // namespace
}  // namespace obscura::test
