// Materials whose diffuseColor or opacity reads a primvar (UsdPreviewSurface spec, "Primvar
// Reading"), through the harness from USD text: a UsdPrimvarReader_float3 on diffuseColor (a
// UsdPrimvarReader_float on opacity) gives each prim bound to the material the primvar it names
// (vertex colours and alphas, as DCCs export them), the reader's fallback where a prim has none,
// and a PointInstancer's displayColor (displayOpacity) per instance.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace obscura::test {
namespace {

using Rgb = std::array<float, 3>;

// A material whose diffuseColor (authored blue, which the reader replaces) reads `varname`,
// through a NodeGraph output as real assets connect it; `fallback` is the reader's line, if any.
std::string readerMaterial(const std::string& varname, const std::string& fallback = "") {
    return "def Material \"Look\"\n{\n"
           "    token outputs:surface.connect = </Look/Surface.outputs:surface>\n"
           "    def Shader \"Surface\"\n    {\n"
           "        uniform token info:id = \"UsdPreviewSurface\"\n"
           "        color3f inputs:diffuseColor = (0.05, 0.05, 0.9)\n"
           "        color3f inputs:diffuseColor.connect = </Look/Colours.outputs:colour>\n"
           "        float inputs:roughness = 0.7\n"
           "        token outputs:surface\n    }\n"
           "    def NodeGraph \"Colours\"\n    {\n"
           "        color3f outputs:colour.connect = </Look/Colours/Reader.outputs:result>\n"
           "        def Shader \"Reader\"\n        {\n"
           "            uniform token info:id = \"UsdPrimvarReader_float3\"\n"
           "            string inputs:varname = \"" + varname + "\"\n" + fallback +
           "            float3 outputs:result\n        }\n    }\n}\n";
}

// A quad bound to the material, centred at x (in the delegate tests' view, [-1.05, 1.05]^2 at
// z = 0), 0.8 units square, with its primvar lines.
std::string quad(const std::string& name, double x, const std::string& primvars) {
    auto corner = [&](double dx, double dy) {
        return "(" + std::to_string(x + dx) + ", " + std::to_string(dy) + ", 0)";
    };
    return "def Mesh \"" + name + "\" (\n    prepend apiSchemas = [\"MaterialBindingAPI\"]\n)\n{\n"
           "    point3f[] points = [" + corner(-0.4, -0.4) + ", " + corner(0.4, -0.4) + ", " + corner(0.4, 0.4) + ", " +
           corner(-0.4, 0.4) + "]\n"
           "    int[] faceVertexCounts = [4]\n    int[] faceVertexIndices = [0, 1, 2, 3]\n" + primvars +
           "    rel material:binding = </Look>\n}\n";
}

// The albedo at a pixel of the 64x64 view (render_fixture.h).
Rgb albedoAt(const std::vector<float>& albedo, int x, int y) {
    const size_t i = (size_t(y) * kWidth + size_t(x)) * 3;
    return {albedo.at(i), albedo.at(i + 1), albedo.at(i + 2)};
}

void expectColour(const Rgb& seen, const Rgb& expected, const std::string& where) {
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], expected[c], 0.02f) << where << ", channel " << c;
}

// Quads at x = -0.5 and 0.5: pixel columns 16 and 48 of row 32.
constexpr int kLeft = 16, kRight = 48, kRow = 32;

TEST(PrimvarReaderStage, DiffuseColorReadsEachPrimsDisplayColor) {
    HostedStage scene(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + readerMaterial("displayColor") +
            quad("Red", -0.5, "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n") +
            quad("Green", 0.5, "    color3f[] primvars:displayColor = [(0.05, 0.7, 0.1)]\n"),
        "reader.usda"));
    std::vector<float> albedo = scene.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.8f, 0.05f, 0.05f}, "red quad");
    expectColour(albedoAt(albedo, kRight, kRow), {0.05f, 0.7f, 0.1f}, "green quad");
    EXPECT_FALSE(scene.warned("not supported"));
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

// Vertex colours of another name (Houdini's Cd), interpolated across the face: the quad's left
// edge red, its right edge green, so its centre is their mean.
TEST(PrimvarReaderStage, AnyPrimvarNameAndInterpolation) {
    HostedStage scene(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + readerMaterial("Cd") +
            quad("Ramp", -0.5,
                 "    color3f[] primvars:displayColor = [(0.9, 0.9, 0.9)]\n"
                 "    color3f[] primvars:Cd = [(0.8, 0, 0), (0, 0.8, 0), (0, 0.8, 0), (0.8, 0, 0)] (\n"
                 "        interpolation = \"vertex\"\n    )\n"),
        "reader.usda"));
    std::vector<float> albedo = scene.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.4f, 0.4f, 0.0f}, "centre of the ramp");
    const Rgb nearLeft = albedoAt(albedo, kLeft - 10, kRow), nearRight = albedoAt(albedo, kLeft + 10, kRow);
    EXPECT_GT(nearLeft[0], 0.6f);
    EXPECT_LT(nearLeft[1], 0.2f);
    EXPECT_GT(nearRight[1], 0.6f);
    EXPECT_LT(nearRight[0], 0.2f);
}

// A prim without the primvar takes the reader's fallback; without one authored, the reader's
// default, zero: never the material's authored diffuseColor, which the connection replaces.
TEST(PrimvarReaderStage, WithoutThePrimvarTheReadersFallback) {
    HostedStage withFallback(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + readerMaterial("Cd", "            float3 inputs:fallback = (0.1, 0.6, 0.3)\n") +
            quad("Plain", -0.5, "") + quad("Coloured", 0.5, "    color3f[] primvars:Cd = [(0.7, 0.2, 0.5)]\n"),
        "reader.usda"));
    std::vector<float> albedo = withFallback.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.1f, 0.6f, 0.3f}, "fallback");
    expectColour(albedoAt(albedo, kRight, kRow), {0.7f, 0.2f, 0.5f}, "primvar");

    HostedStage withoutFallback(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + readerMaterial("Cd") + quad("Plain", -0.5, ""), "reader.usda"));
    expectColour(albedoAt(withoutFallback.renderAlbedo(), kLeft, kRow), {0.0f, 0.0f, 0.0f}, "the reader's default");
}

// Hydra's instance primvars reach a material that reads displayColor: each instance its own.
TEST(PrimvarReaderStage, InstancesColourThroughTheReader) {
    const std::string text =
        "#usda 1.0\n" + usdaCamera() + readerMaterial("displayColor") +
        "def PointInstancer \"Instancer\"\n{\n"
        "    rel prototypes = [</Instancer/Prototypes/Quad>]\n"
        "    int[] protoIndices = [0, 0]\n"
        "    point3f[] positions = [(-0.5, 0, 0), (0.5, 0, 0)]\n"
        "    color3f[] primvars:displayColor = [(0.05, 0.8, 0.05), (0.05, 0.05, 0.8)] (\n"
        "        interpolation = \"vertex\"\n    )\n"
        "    def Scope \"Prototypes\"\n    {\n" +
        quad("Quad", 0.0, "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n") + "    }\n}\n";
    HostedStage scene(usda::Stage::openFromString(text, "reader.usda"));
    std::vector<float> albedo = scene.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.05f, 0.8f, 0.05f}, "first instance");
    expectColour(albedoAt(albedo, kRight, kRow), {0.05f, 0.05f, 0.8f}, "second instance");
}

// An edit of the reader (another primvar) reaches the prims bound to the material: the host marks
// the material and the quad, whose displayColor it serves from another primvar now.
TEST(PrimvarReaderStage, EditingTheReaderRecoloursTheBoundPrims) {
    const std::string primvars =
        "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n    color3f[] primvars:Cd = [(0.05, 0.05, 0.8)]\n";
    HostedStage scene(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + readerMaterial("displayColor") + quad("Quad", -0.5, primvars), "reader.usda"));
    expectColour(albedoAt(scene.renderAlbedo(), kLeft, kRow), {0.8f, 0.05f, 0.05f}, "displayColor");
    EXPECT_EQ(scene.adopt(usda::Stage::openFromString(
                  "#usda 1.0\n" + usdaCamera() + readerMaterial("Cd") + quad("Quad", -0.5, primvars), "reader.usda")),
              2u);
    expectColour(albedoAt(scene.renderAlbedo(), kLeft, kRow), {0.05f, 0.05f, 0.8f}, "Cd after the edit");
}

// A material whose opacity reads a primvar (its own authored 0.9 replaced), red and matte.
std::string opacityReaderMaterial(const std::string& varname, const std::string& fallback = "") {
    return "def Material \"Look\"\n{\n"
           "    token outputs:surface.connect = </Look/Surface.outputs:surface>\n"
           "    def Shader \"Surface\"\n    {\n"
           "        uniform token info:id = \"UsdPreviewSurface\"\n"
           "        color3f inputs:diffuseColor = (0.8, 0.05, 0.05)\n"
           "        float inputs:opacity = 0.9\n"
           "        float inputs:opacity.connect = </Look/Alpha.outputs:result>\n"
           "        token outputs:surface\n    }\n"
           "    def Shader \"Alpha\"\n    {\n"
           "        uniform token info:id = \"UsdPrimvarReader_float\"\n"
           "        string inputs:varname = \"" + varname + "\"\n" + fallback +
           "        float outputs:result\n    }\n}\n";
}

// The colour AOV's alpha at a pixel: the opacity of a transparent surface over nothing.
float alphaAt(const std::vector<float>& color, int x, int y) { return color.at((size_t(y) * kWidth + size_t(x)) * 4 + 3); }

TEST(PrimvarReaderStage, OpacityReadsEachPrimsDisplayOpacity) {
    HostedStage scene(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + opacityReaderMaterial("displayOpacity") +
            quad("Half", -0.5, "    float[] primvars:displayOpacity = [0.5]\n") +
            quad("Whole", 0.5, "    float[] primvars:displayOpacity = [1]\n"),
        "reader.usda"));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.5f, 1.0f / 255.0f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 1.0f, 1.0f / 255.0f);
    EXPECT_FALSE(scene.warned("not supported"));
}

// Opacity of another name, varying over the quad (0.2 at its left edge, 1 at its right), and the
// reader's fallback (unauthored: zero) on a quad without it.
TEST(PrimvarReaderStage, OpacityOfAnyPrimvarOrTheFallback) {
    HostedStage scene(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + opacityReaderMaterial("alpha") +
            quad("Ramp", -0.5,
                 "    float[] primvars:alpha = [0.2, 1, 1, 0.2] (\n        interpolation = \"vertex\"\n    )\n") +
            quad("Without", 0.5, ""),
        "reader.usda"));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.6f, 0.02f);
    EXPECT_LT(alphaAt(color, kLeft - 10, kRow), 0.4f);
    EXPECT_GT(alphaAt(color, kLeft + 10, kRow), 0.8f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 0.0f, 1.0f / 255.0f);

    HostedStage withFallback(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + opacityReaderMaterial("alpha", "            float inputs:fallback = 0.3\n") +
            quad("Without", 0.5, ""),
        "reader.usda"));
    EXPECT_NEAR(alphaAt(withFallback.renderAov("color", 4), kRight, kRow), 0.3f, 1.0f / 255.0f);
}

// Hydra's instance primvars reach a material whose opacity reads displayOpacity.
TEST(PrimvarReaderStage, InstanceOpacityThroughTheReader) {
    const std::string text =
        "#usda 1.0\n" + usdaCamera() + opacityReaderMaterial("displayOpacity") +
        "def PointInstancer \"Instancer\"\n{\n"
        "    rel prototypes = [</Instancer/Prototypes/Quad>]\n"
        "    int[] protoIndices = [0, 0]\n"
        "    point3f[] positions = [(-0.5, 0, 0), (0.5, 0, 0)]\n"
        "    float[] primvars:displayOpacity = [0.25, 1] (\n        interpolation = \"vertex\"\n    )\n"
        "    def Scope \"Prototypes\"\n    {\n" +
        quad("Quad", 0.0, "    float[] primvars:displayOpacity = [0.6]\n") + "    }\n}\n";
    HostedStage scene(usda::Stage::openFromString(text, "reader.usda"));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.25f, 1.0f / 255.0f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 1.0f, 1.0f / 255.0f);
}

// Without a reader, the material's diffuseColor wins over displayColor, as before.
TEST(PrimvarReaderStage, WithoutAReaderTheMaterialsColour) {
    const std::string material =
        "def Material \"Look\"\n{\n"
        "    token outputs:surface.connect = </Look/Surface.outputs:surface>\n"
        "    def Shader \"Surface\"\n    {\n"
        "        uniform token info:id = \"UsdPreviewSurface\"\n"
        "        color3f inputs:diffuseColor = (0.05, 0.05, 0.9)\n"
        "        token outputs:surface\n    }\n}\n";
    HostedStage scene(usda::Stage::openFromString(
        "#usda 1.0\n" + usdaCamera() + material + quad("Quad", -0.5, "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n"),
        "reader.usda"));
    expectColour(albedoAt(scene.renderAlbedo(), kLeft, kRow), {0.05f, 0.05f, 0.9f}, "material");
}

}  // namespace
}  // namespace obscura::test
