// The harness's flattening of UsdShade texture networks, end to end through UsdSceneHost and the
// plugin: tests/harness/data/textured.usda binds a Material whose UsdPreviewSurface reads its
// diffuseColor from a UsdUVTexture (an 8x8 PNG of four colour blocks, named relative to the
// layer), whose st comes from a UsdPrimvarReader_float2 with its varname on the material's
// interface, reading an indexed face-varying primvar "uv".
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <variant>

namespace obscura::test {
namespace {

void expectLinear(const std::vector<float>& albedo, int x, int y, std::array<int, 3> srgbCodes, const char* what) {
    for (size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(albedo.at((size_t(y) * kWidth + size_t(x)) * 3 + c), srgb8Exact(srgbCodes[c]), 0.004f)
            << what << " channel " << c;
}

TEST(TexturedUsda, ThePlaneShowsTheFourBlocks) {
    HostedStage scene(usda::Stage::open(OBSCURA_TEST_DATA_DIR "/textured.usda"));
    scene.setBool("textures:compression", false);  // the blocks' exact codes, not BC1's 5:6:5 endpoints
    auto albedo = scene.renderAlbedo();
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_FALSE(scene.warned("not supported")) << "the texture network was not flattened";
    expectLinear(albedo, 16, 16, {200, 40, 40}, "top left");
    expectLinear(albedo, 48, 16, {40, 200, 40}, "top right");
    expectLinear(albedo, 16, 48, {40, 40, 200}, "bottom left");
    expectLinear(albedo, 48, 48, {220, 220, 60}, "bottom right");
}

TEST(TexturedUsda, TexturesOnOtherInputsStillWarn) {
    // specularColor is not textured by the delegate: its connection keeps the warning, and the
    // authored value is used.
    const std::string text = R"(#usda 1.0
def Material "M"
{
    token outputs:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:specularColor = (0.5, 0.5, 0.5)
        color3f inputs:specularColor.connect = </M/Texture.outputs:rgb>
        token outputs:surface
    }
    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @textures/checker.png@
        float3 outputs:rgb
    }
}
)";
    HostedStage scene(usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/inline.usda"));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    EXPECT_EQ(sd.getValue(sd.userData, "/M", "inputs:specularColor", 0.0, &value), OBSCURA_OK);
    EXPECT_TRUE(scene.warned("inputs:specularColor is connected"));
    EXPECT_EQ(sd.getValue(sd.userData, "/M", "obscura:specularColor:file", 0.0, &value), OBSCURA_ERROR_NOT_FOUND);
}

TEST(TexturedUsda, AnisotropyInputsReachTheDelegateAndTheirTexturesWarn) {
    // obscura:anisotropy and obscura:anisotropyRotation on a UsdPreviewSurface are served like its
    // own inputs; the delegate reads them as constants, so a connected texture keeps the warning
    // and the authored value is used.
    const std::string text = R"(#usda 1.0
def Material "M"
{
    token outputs:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        float inputs:obscura:anisotropy = 0.7
        float inputs:obscura:anisotropy.connect = </M/Texture.outputs:r>
        float inputs:obscura:anisotropyRotation = 45
        token outputs:surface
    }
    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @textures/checker.png@
        float outputs:r
    }
}
)";
    HostedStage scene(usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/inline.usda"));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "inputs:obscura:anisotropy", 0.0, &value), OBSCURA_OK);
    EXPECT_FLOAT_EQ(static_cast<const float*>(value.data)[0], 0.7f);
    EXPECT_TRUE(scene.warned("inputs:obscura:anisotropy is connected"));
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "inputs:obscura:anisotropyRotation", 0.0, &value), OBSCURA_OK);
    EXPECT_FLOAT_EQ(static_cast<const float*>(value.data)[0], 45.0f);
}

TEST(TexturedUsda, OcclusionTextureIsFlattenedLikeTheOtherInputs) {
    // inputs:occlusion (a constant, and a UsdUVTexture's r output) reaches the delegate as the
    // constant and obscura:occlusion:*, with no "connected" warning.
    const std::string text = R"(#usda 1.0
def Material "M"
{
    token outputs:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        float inputs:occlusion = 0.75
        float inputs:occlusion.connect = </M/Texture.outputs:r>
        token outputs:surface
    }
    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @textures/checker.png@
        token inputs:sourceColorSpace = "raw"
        float outputs:r
    }
}
)";
    HostedStage scene(usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/inline.usda"));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "inputs:occlusion", 0.0, &value), OBSCURA_OK);
    EXPECT_FLOAT_EQ(static_cast<const float*>(value.data)[0], 0.75f);
    EXPECT_FALSE(scene.warned("inputs:occlusion is connected"));
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "obscura:occlusion:file", 0.0, &value), OBSCURA_OK);
    EXPECT_EQ(std::filesystem::path(static_cast<const char* const*>(value.data)[0]),
              std::filesystem::absolute(OBSCURA_TEST_DATA_DIR "/textures/checker.png").lexically_normal());
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "obscura:occlusion:channel", 0.0, &value), OBSCURA_OK);
    EXPECT_EQ(std::string(static_cast<const char* const*>(value.data)[0]), "r");
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "obscura:occlusion:sourceColorSpace", 0.0, &value), OBSCURA_OK);
    EXPECT_EQ(std::string(static_cast<const char* const*>(value.data)[0]), "raw");
}

TEST(TexturedUsda, DomeTextureFileIsResolvedAgainstItsLayer) {
    // Hosts resolve asset paths: the delegate gets the file's absolute path.
    HostedStage scene(usda::Stage::open(OBSCURA_TEST_DATA_DIR "/dome.usda"));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/Sky", "inputs:texture:file", 0.0, &value), OBSCURA_OK);
    ASSERT_EQ(value.type, OBSCURA_VALUE_TOKEN);
    std::string file = static_cast<const char* const*>(value.data)[0];
    EXPECT_EQ(std::filesystem::path(file),
              std::filesystem::absolute(OBSCURA_TEST_DATA_DIR "/textures/checker.png").lexically_normal());
    EXPECT_TRUE(std::filesystem::exists(file)) << file;
}

// tests/harness/data/nodegraph.usda: a material's outputs:surface through a NodeGraph output to
// the UsdPreviewSurface inside it, its diffuseColor through the NodeGraph's interface input to
// the Material's (left half); a texture's rgb through a NodeGraph output (right half).
TEST(NodeGraphUsda, ConnectionsResolveThroughNodeGraphsAndInterfaces) {
    HostedStage scene(usda::Stage::open(OBSCURA_TEST_DATA_DIR "/nodegraph.usda"));
    scene.setBool("textures:compression", false);  // the blocks' exact codes, not BC1's 5:6:5 endpoints
    auto albedo = scene.renderAlbedo();
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
    expectLinear(albedo, 16, 16, {180, 60, 20}, "the Material's baseColor");
    expectLinear(albedo, 16, 48, {180, 60, 20}, "the Material's baseColor");
    expectLinear(albedo, 40, 16, {200, 40, 40}, "top left block");
    expectLinear(albedo, 56, 16, {40, 200, 40}, "top right block");
    expectLinear(albedo, 40, 48, {40, 40, 200}, "bottom left block");
    expectLinear(albedo, 56, 48, {220, 220, 60}, "bottom right block");
    // A value held on the NodeGraph's own interface.
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/Looks/Interface", "inputs:roughness", 0.0, &value), OBSCURA_OK);
    EXPECT_FLOAT_EQ(static_cast<const float*>(value.data)[0], 0.4f);
}

TEST(NodeGraphUsda, BrokenConnectionsAreReportedWhereAuthored) {
    // Each material breaks one link; each warning names the material and the line of the
    // connection, the prims still render (with no material, or the input's own value).
    const std::string text = R"(#usda 1.0
def Material "MissingOutput"
{
    token outputs:surface.connect = </MissingOutput/Graph.outputs:nothing>
    def NodeGraph "Graph"
    {
    }
}
def Material "Unconnected"
{
    token outputs:surface.connect = </Unconnected/Graph.outputs:surface>
    def NodeGraph "Graph"
    {
        token outputs:surface
    }
}
def Material "Cycle"
{
    token outputs:surface.connect = </Cycle/Graph.outputs:a>
    def NodeGraph "Graph"
    {
        token outputs:a.connect = </Cycle/Graph.outputs:b>
        token outputs:b.connect = </Cycle/Graph.outputs:a>
    }
}
def Material "OtherShader"
{
    token outputs:surface.connect = </OtherShader/Graph.outputs:surface>
    def NodeGraph "Graph"
    {
        token outputs:surface.connect = </OtherShader/Graph/Standard.outputs:surface>
        def Shader "Standard"
        {
            uniform token info:id = "ND_standard_surface_surfaceshader"
            token outputs:surface
        }
    }
}
def Material "MissingInterface"
{
    token outputs:surface.connect = </MissingInterface/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        float inputs:roughness = 0.25
        float inputs:roughness.connect = </MissingInterface.inputs:rough>
        token outputs:surface
    }
}
)";
    HostedStage scene(usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/broken.usda"));
    auto located = [&](const std::string& fragment, int line) {
        for (const auto& m : scene.host->messages())
            if (m.text.find(fragment) != std::string::npos)
                return m.where.file == OBSCURA_TEST_DATA_DIR "/broken.usda" && m.where.line == line;
        ADD_FAILURE() << "no message with " << fragment;
        return false;
    };
    EXPECT_TRUE(located("/MissingOutput: outputs:surface: its connection target </MissingOutput/Graph.outputs:nothing> "
                        "does not exist; material skipped", 4));
    EXPECT_TRUE(located("/Unconnected: outputs:surface: </Unconnected/Graph.outputs:surface> is an output connected "
                        "to nothing", 11));
    EXPECT_TRUE(located("/Cycle: outputs:surface: its connections form a cycle", 19));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/MissingInterface", "inputs:roughness", 0.0, &value), OBSCURA_OK);
    EXPECT_FLOAT_EQ(static_cast<const float*>(value.data)[0], 0.25f);
    EXPECT_TRUE(located("/MissingInterface: inputs:roughness: its connection target </MissingInterface.inputs:rough> "
                        "does not exist", 46));
    // A MaterialX Standard Surface is mapped, with its defaults: base 0.8 of a white base_color.
    ASSERT_EQ(sd.getValue(sd.userData, "/OtherShader", "inputs:diffuseColor", 0.0, &value), OBSCURA_OK);
    EXPECT_FLOAT_EQ(static_cast<const float*>(value.data)[0], 0.8f);
    for (const auto& m : scene.host->messages()) EXPECT_EQ(m.text.find("/OtherShader"), std::string::npos) << m.text;
}

TEST(NodeGraphUsda, AnAnimatedInterfaceInputAnimatesTheMaterial) {
    // The colour is sampled on the Material's interface only; the surface shader's input connects
    // to it through the NodeGraph's. Each frame's albedo follows the samples (sRGB codes 200 then 40).
    const std::string text = "#usda 1.0\n" + usdaCamera() + R"(def Mesh "Plane"
{
    point3f[] points = [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    uniform token subdivisionScheme = "none"
    rel material:binding = </M>
}
def Material "M"
{
    color3f inputs:tint.timeSamples = { 0: (0.577581, 0.577581, 0.577581), 1: (0.021219, 0.021219, 0.021219) }
    token outputs:surface.connect = </M/Graph.outputs:surface>
    def NodeGraph "Graph"
    {
        color3f inputs:tint.connect = </M.inputs:tint>
        token outputs:surface.connect = </M/Graph/Surface.outputs:surface>
        def Shader "Surface"
        {
            uniform token info:id = "UsdPreviewSurface"
            color3f inputs:diffuseColor.connect = </M/Graph.inputs:tint>
            token outputs:surface
        }
    }
}
)";
    HostedStage scene(usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/animated.usda"));
    auto first = scene.renderAov("albedo", 3, 0.0);
    ASSERT_EQ(first.size(), size_t(kWidth) * kHeight * 3);
    expectLinear(first, 32, 32, {200, 200, 200}, "time 0");
    ASSERT_EQ(scene.host->markTimeVarying(scene.api(), scene.delegate), OBSCURA_OK);
    auto second = scene.renderAov("albedo", 3, 1.0);
    ASSERT_EQ(second.size(), size_t(kWidth) * kHeight * 3);
    expectLinear(second, 32, 32, {40, 40, 40}, "time 1");
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

}  // namespace
}  // namespace obscura::test
