// Texture-coordinate transforms through the harness's scene host and the plugin: UsdTransform2d
// shaders between a UsdUVTexture's inputs:st and its UsdPrimvarReader_float2 (UsdPreviewSurface
// spec: st' = translation + rotate(rotation) (scale st), rotation counter-clockwise in degrees),
// chained or with inputs on the material's interface, and MaterialX ND_tiledimage's uvtiling and
// uvoffset (uv' = uv uvtiling - uvoffset, MaterialX's NG_tiledimage). The plane fills the view
// with st from 0 to 1 and the texture is tests/harness/data/textures/checker.png, four colour
// blocks, repeating.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace obscura::test {
namespace {

// textured.usda's camera and plane; the material's diffuseColor texture reads raw texels with st
// from `stSource` (an output among `shaders`, which can reach the primvar reader "Reader").
std::string planeWith(const std::string& shaders, const std::string& stSource, const std::string& interface = "") {
    return R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Y"
)
)" + usdaCamera() + R"(def Mesh "Plane"
{
    point3f[] points = [(-1.04775, -1.04775, 0), (1.04775, -1.04775, 0), (1.04775, 1.04775, 0), (-1.04775, 1.04775, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    uniform token subdivisionScheme = "none"
    texCoord2f[] primvars:st = [(0, 0), (1, 0), (1, 1), (0, 1)] (
        interpolation = "vertex"
    )
    rel material:binding = </M>
}
def Material "M"
{
)" + interface + R"(
    token outputs:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:diffuseColor.connect = </M/Texture.outputs:rgb>
        token outputs:surface
    }
    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @textures/checker.png@
        token inputs:sourceColorSpace = "raw"
        token inputs:wrapS = "repeat"
        token inputs:wrapT = "repeat"
        float2 inputs:st.connect = <)" + stSource + R"(>
        float3 outputs:rgb
    }
    def Shader "Reader"
    {
        uniform token info:id = "UsdPrimvarReader_float2"
        token inputs:varname = "st"
        float2 outputs:result
    }
)" + shaders + R"(
}
)";
}

std::string transform2d(const std::string& name, const std::string& in, const std::string& inputs) {
    return "    def Shader \"" + name + "\"\n    {\n        uniform token info:id = \"UsdTransform2d\"\n" +
           "        float2 inputs:in.connect = <" + in + ">\n" + inputs + "        float2 outputs:result\n    }\n";
}

auto open(const std::string& text) { return usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/inline.usda"); }

// The rows the host serves as obscura:diffuseColor:transformS and transformT.
std::array<std::array<float, 3>, 2> servedRows(HostedStage& scene) {
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    std::array<std::array<float, 3>, 2> rows{};
    const char* names[2] = {"obscura:diffuseColor:transformS", "obscura:diffuseColor:transformT"};
    for (size_t r = 0; r < 2; ++r) {
        ObscuraValue value{};
        EXPECT_EQ(sd.getValue(sd.userData, "/M", names[r], 0.0, &value), OBSCURA_OK) << names[r];
        if (value.type != OBSCURA_VALUE_FLOAT3) {
            ADD_FAILURE() << names[r] << " is not a float3";
            continue;
        }
        for (size_t i = 0; i < 3; ++i) rows[r][i] = static_cast<const float*>(value.data)[i];
    }
    return rows;
}

void expectRows(const std::array<std::array<float, 3>, 2>& rows, std::array<float, 3> s, std::array<float, 3> t,
                const char* what) {
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(rows[0][i], s[i], 1e-5f) << what << ": transformS[" << i << "]";
        EXPECT_NEAR(rows[1][i], t[i], 1e-5f) << what << ": transformT[" << i << "]";
    }
}

// checker.png's blocks, raw: top left, top right, bottom left, bottom right.
constexpr std::array<std::array<int, 3>, 4> kBlocks = {{{200, 40, 40}, {40, 200, 40}, {40, 40, 200}, {220, 220, 60}}};

// The block a repeating lookup at (s, t) lands in.
size_t blockAt(double s, double t) {
    const double u = s - std::floor(s), v = 1.0 - (t - std::floor(t));
    return (v < 0.5 ? 0 : 2) + (u < 0.5 ? 0 : 1);
}

// Each 16-pixel cell's centre shows the block of map(st).
template <typename Map>
void expectBlocks(const std::vector<float>& albedo, Map map, const char* what) {
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    for (int y = 8; y < kHeight; y += 16)
        for (int x = 8; x < kWidth; x += 16) {
            const auto [s, t] = map((x + 0.5) / kWidth, 1.0 - (y + 0.5) / kHeight);
            const auto& block = kBlocks[blockAt(s, t)];
            for (size_t c = 0; c < 3; ++c)
                EXPECT_NEAR(albedo[(size_t(y) * kWidth + size_t(x)) * 3 + c], block[c] / 255.0f, 0.004f)
                    << what << ": pixel (" << x << ", " << y << ") channel " << c;
        }
}

std::vector<float> render(HostedStage& scene) {
    scene.setBool("textures:compression", false);  // the blocks' exact codes
    auto albedo = scene.renderAlbedo();
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
    return albedo;
}

TEST(TextureTransformUsda, ScaleTilesTheTexture) {
    HostedStage scene(open(planeWith(transform2d("Tiling", "/M/Reader.outputs:result", "        float2 inputs:scale = (2, 2)\n"),
                                     "/M/Tiling.outputs:result")));
    expectRows(servedRows(scene), {2, 0, 0}, {0, 2, 0}, "scale (2, 2)");
    // The reader's primvar is still found behind the transform.
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "obscura:diffuseColor:st", 0.0, &value), OBSCURA_OK);
    EXPECT_EQ(std::string(static_cast<const char* const*>(value.data)[0]), "st");
    expectBlocks(render(scene), [](double s, double t) { return std::pair{2 * s, 2 * t}; }, "scale (2, 2)");
}

TEST(TextureTransformUsda, RotationIsCounterClockwiseAfterTheScaleAndBeforeTheTranslation) {
    HostedStage scene(open(planeWith(transform2d("Placed", "/M/Reader.outputs:result",
                                                 "        float2 inputs:scale = (1, 2)\n"
                                                 "        float inputs:rotation = 90\n"
                                                 "        float2 inputs:translation = (0.5, 0.25)\n"),
                                     "/M/Placed.outputs:result")));
    // rotate(90) (1 s, 2 t) = (-2 t, s), then translated.
    expectRows(servedRows(scene), {0, -2, 0.5f}, {1, 0, 0.25f}, "scale, rotation, translation");
    expectBlocks(render(scene), [](double s, double t) { return std::pair{-2 * t + 0.5, s + 0.25}; },
                 "scale, rotation, translation");
}

TEST(TextureTransformUsda, ChainedTransformsComposeFromTheReaderOut) {
    // The reader's st is scaled by Inner first, then shifted by Outer; Outer's translation comes
    // from the material's interface.
    const std::string shaders =
        transform2d("Inner", "/M/Reader.outputs:result", "        float2 inputs:scale = (2, 2)\n") +
        transform2d("Outer", "/M/Inner.outputs:result", "        float2 inputs:translation.connect = </M.inputs:shift>\n");
    HostedStage scene(open(planeWith(shaders, "/M/Outer.outputs:result", "    float2 inputs:shift = (0.5, 0)\n")));
    expectRows(servedRows(scene), {2, 0, 0.5f}, {0, 2, 0}, "scale then shift");
    expectBlocks(render(scene), [](double s, double t) { return std::pair{2 * s + 0.5, 2 * t}; }, "scale then shift");
}

TEST(TextureTransformUsda, NonFiniteInputsAreReportedAndTheTransformIgnored) {
    HostedStage scene(open(planeWith(transform2d("Bad", "/M/Reader.outputs:result", "        float2 inputs:scale = (inf, 2)\n"),
                                     "/M/Bad.outputs:result")));
    expectRows(servedRows(scene), {1, 0, 0}, {0, 1, 0}, "ignored");
    EXPECT_TRUE(scene.warned("/M/Bad.inputs:scale must be 2 finite numbers")) << "not reported";
}

// A MaterialX Standard Surface whose base colour is an ND_tiledimage_color3 reading the texture
// through ND_texcoord_vector2 with `tiling`.
std::string materialxPlane(const std::string& tiling) {
    std::string text = planeWith("", "/M/Reader.outputs:result");
    const std::string surface = R"(    def Shader "Surface"
    {
        uniform token info:id = "ND_standard_surface_surfaceshader"
        float inputs:base = 1
        color3f inputs:base_color.connect = </M/Image.outputs:out>
        token outputs:surface
    }
    def Shader "Image"
    {
        uniform token info:id = "ND_tiledimage_color3"
        asset inputs:file = @textures/checker.png@
        float2 inputs:texcoord.connect = </M/Coords.outputs:out>
)" + tiling + R"(        color3f outputs:out
    }
    def Shader "Coords"
    {
        uniform token info:id = "ND_texcoord_vector2"
        float2 outputs:out
    }
)";
    const size_t begin = text.find("    def Shader \"Surface\""), end = text.find("    def Shader \"Reader\"");
    return text.replace(begin, end - begin, surface);
}

TEST(TextureTransformUsda, MaterialXTilingMatchesUsdTransform2dScale) {
    HostedStage transformed(open(planeWith(transform2d("Tiling", "/M/Reader.outputs:result", "        float2 inputs:scale = (2, 2)\n"),
                                           "/M/Tiling.outputs:result")));
    HostedStage tiled(open(materialxPlane("        float2 inputs:uvtiling = (2, 2)\n")));
    expectRows(servedRows(tiled), {2, 0, 0}, {0, 2, 0}, "uvtiling (2, 2)");
    const std::vector<float> reference = render(transformed), image = render(tiled);
    ASSERT_EQ(image.size(), reference.size());
    for (size_t i = 0; i < image.size(); ++i) ASSERT_NEAR(image[i], reference[i], 0.004f) << "value " << i;
    expectBlocks(image, [](double s, double t) { return std::pair{2 * s, 2 * t}; }, "uvtiling (2, 2)");
}

TEST(TextureTransformUsda, MaterialXOffsetIsSubtractedAfterTheTiling) {
    HostedStage tiled(open(materialxPlane("        float2 inputs:uvtiling = (2, 1)\n"
                                          "        float2 inputs:uvoffset = (0.5, 0.5)\n")));
    expectRows(servedRows(tiled), {2, 0, -0.5f}, {0, 1, -0.5f}, "uvtiling (2, 1), uvoffset (0.5, 0.5)");
    expectBlocks(render(tiled), [](double s, double t) { return std::pair{2 * s - 0.5, t - 0.5}; },
                 "uvtiling (2, 1), uvoffset (0.5, 0.5)");
}

}  // namespace
}  // namespace obscura::test
