// Materials whose diffuseColor or opacity reads a primvar (UsdPreviewSurface spec, "Primvar
// Reading"), through the harness from USD text: a UsdPrimvarReader_float3 on diffuseColor (a
// UsdPrimvarReader_float on opacity) gives each prim bound to the material the primvar it names
// (vertex colours and alphas, as DCCs export them), the reader's fallback where a prim has none,
// and a PointInstancer's primvar of that name per instance; a MaterialX ND_geompropvalue
// on a surface's base colour (times its constant factors) or opacity reads the same way.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <string>
#include <variant>

namespace obscura::test {
namespace {

using Rgb = std::array<float, 3>;

// A material whose `input` (a declaration, "color3f inputs:diffuseColor") is authored `authored`,
// which the connection replaces, and connected through a NodeGraph output, as real assets connect
// it, to a primvar reader `readerId` of `varname`; `fallback` is the reader's line, if any.
std::string readerLook(const std::string& input, const std::string& authored, const std::string& readerId,
                       const std::string& varname, const std::string& fallback) {
    const std::string type = input.substr(0, input.find(' '));
    return "def Material \"Look\"\n{\n"
           "    token outputs:surface.connect = </Look/Surface.outputs:surface>\n"
           "    def Shader \"Surface\"\n    {\n"
           "        uniform token info:id = \"UsdPreviewSurface\"\n"
           "        " + input + " = " + authored + "\n"
           "        " + input + ".connect = </Look/Primvars.outputs:value>\n"
           "        token outputs:surface\n    }\n"
           "    def NodeGraph \"Primvars\"\n    {\n"
           "        " + type + " outputs:value.connect = </Look/Primvars/Reader.outputs:result>\n"
           "        def Shader \"Reader\"\n        {\n"
           "            uniform token info:id = \"" + readerId + "\"\n"
           "            string inputs:varname = \"" + varname + "\"\n" + fallback +
           "            " + type + " outputs:result\n        }\n    }\n}\n";
}

// diffuseColor (authored blue) read from `varname`.
std::string readerMaterial(const std::string& varname, const std::string& fallback = "") {
    return readerLook("color3f inputs:diffuseColor", "(0.05, 0.05, 0.9)", "UsdPrimvarReader_float3", varname, fallback);
}

// opacity (authored 0.9) read from `varname`; the diffuse colour is the default grey.
std::string opacityReaderMaterial(const std::string& varname, const std::string& fallback = "") {
    return readerLook("float inputs:opacity", "0.9", "UsdPrimvarReader_float", varname, fallback);
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

// Two instances of a quad bound to `material` (at x = -0.5 and 0.5), with the instancer's and the
// quad's primvar lines.
std::string instancedQuads(const std::string& material, const std::string& instancePrimvars,
                           const std::string& quadPrimvars) {
    return material +
           "def PointInstancer \"Instancer\"\n{\n"
           "    rel prototypes = [</Instancer/Prototypes/Quad>]\n"
           "    int[] protoIndices = [0, 0]\n"
           "    point3f[] positions = [(-0.5, 0, 0), (0.5, 0, 0)]\n" +
           instancePrimvars + "    def Scope \"Prototypes\"\n    {\n" + quad("Quad", 0.0, quadPrimvars) + "    }\n}\n";
}

// The albedo at a pixel of the 64x64 view (render_fixture.h).
Rgb albedoAt(const std::vector<float>& albedo, int x, int y) {
    const size_t i = (size_t(y) * kWidth + size_t(x)) * 3;
    return {albedo.at(i), albedo.at(i + 1), albedo.at(i + 2)};
}

void expectColour(const Rgb& seen, const Rgb& expected, const std::string& where) {
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], expected[c], 0.02f) << where << ", channel " << c;
}

// A stage of `body` (a material, quads) under the delegate tests' camera.
std::variant<std::unique_ptr<usda::Stage>, usda::Error> stageOf(const std::string& body) {
    return usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + body, "reader.usda");
}

// Quads at x = -0.5 and 0.5: pixel columns 16 and 48 of row 32.
constexpr int kLeft = 16, kRight = 48, kRow = 32;

TEST(PrimvarReaderStage, DiffuseColorReadsEachPrimsDisplayColor) {
    HostedStage scene(stageOf(readerMaterial("displayColor") +
            quad("Red", -0.5, "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n") +
            quad("Green", 0.5, "    color3f[] primvars:displayColor = [(0.05, 0.7, 0.1)]\n")));
    std::vector<float> albedo = scene.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.8f, 0.05f, 0.05f}, "red quad");
    expectColour(albedoAt(albedo, kRight, kRow), {0.05f, 0.7f, 0.1f}, "green quad");
    EXPECT_FALSE(scene.warned("not supported"));
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

// Vertex colours of another name (Houdini's Cd), interpolated across the face: the quad's left
// edge red, its right edge green, so its centre is their mean.
TEST(PrimvarReaderStage, AnyPrimvarNameAndInterpolation) {
    HostedStage scene(stageOf(readerMaterial("Cd") +
            quad("Ramp", -0.5,
                 "    color3f[] primvars:displayColor = [(0.9, 0.9, 0.9)]\n"
                 "    color3f[] primvars:Cd = [(0.8, 0, 0), (0, 0.8, 0), (0, 0.8, 0), (0.8, 0, 0)] (\n"
                 "        interpolation = \"vertex\"\n    )\n")));
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
    HostedStage withFallback(stageOf(readerMaterial("Cd", "            float3 inputs:fallback = (0.1, 0.6, 0.3)\n") +
            quad("Plain", -0.5, "") + quad("Coloured", 0.5, "    color3f[] primvars:Cd = [(0.7, 0.2, 0.5)]\n")));
    std::vector<float> albedo = withFallback.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.1f, 0.6f, 0.3f}, "fallback");
    expectColour(albedoAt(albedo, kRight, kRow), {0.7f, 0.2f, 0.5f}, "primvar");

    HostedStage withoutFallback(stageOf(readerMaterial("Cd") + quad("Plain", -0.5, "")));
    expectColour(albedoAt(withoutFallback.renderAlbedo(), kLeft, kRow), {0.0f, 0.0f, 0.0f}, "the reader's default");
}

// Hydra's instance primvars reach a material that reads displayColor: each instance its own.
TEST(PrimvarReaderStage, InstancesColourThroughTheReader) {
    HostedStage scene(stageOf(
        instancedQuads(readerMaterial("displayColor"),
                       "    color3f[] primvars:displayColor = [(0.05, 0.8, 0.05), (0.05, 0.05, 0.8)] (\n"
                       "        interpolation = \"vertex\"\n    )\n",
                       "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n")));
    std::vector<float> albedo = scene.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.05f, 0.8f, 0.05f}, "first instance");
    expectColour(albedoAt(albedo, kRight, kRow), {0.05f, 0.05f, 0.8f}, "second instance");
}

// Instance primvars of any name, as Houdini writes Cd on its instancers: the prototypes' material
// reads Cd, and the instancer's per-instance Cd colours each instance; an instancer without it
// leaves the prototype its own.
TEST(PrimvarReaderStage, InstancesColourThroughAReaderOfAnyName) {
    const std::string quadCd = "    color3f[] primvars:Cd = [(0.8, 0.05, 0.05)]\n";
    HostedStage scene(stageOf(
        instancedQuads(readerMaterial("Cd"),
                       "    color3f[] primvars:Cd = [(0.05, 0.8, 0.05), (0.05, 0.05, 0.8)] (\n"
                       "        interpolation = \"vertex\"\n    )\n"
                       "    color3f[] primvars:displayColor = [(0.9, 0.9, 0.9), (0.9, 0.9, 0.9)] (\n"
                       "        interpolation = \"vertex\"\n    )\n",
                       quadCd)));
    std::vector<float> albedo = scene.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.05f, 0.8f, 0.05f}, "first instance");
    expectColour(albedoAt(albedo, kRight, kRow), {0.05f, 0.05f, 0.8f}, "second instance");
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);

    HostedStage plain(stageOf(instancedQuads(readerMaterial("Cd"), "", quadCd)));
    std::vector<float> own = plain.renderAlbedo();
    expectColour(albedoAt(own, kLeft, kRow), {0.8f, 0.05f, 0.05f}, "first instance, the quad's own");
    expectColour(albedoAt(own, kRight, kRow), {0.8f, 0.05f, 0.05f}, "second instance, the quad's own");
}

// An edit of the reader (another primvar) reaches the prims bound to the material: the host marks
// the material and the quad, whose displayColor it serves from another primvar now.
TEST(PrimvarReaderStage, EditingTheReaderRecoloursTheBoundPrims) {
    const std::string primvars =
        "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n    color3f[] primvars:Cd = [(0.05, 0.05, 0.8)]\n";
    HostedStage scene(stageOf(readerMaterial("displayColor") + quad("Quad", -0.5, primvars)));
    expectColour(albedoAt(scene.renderAlbedo(), kLeft, kRow), {0.8f, 0.05f, 0.05f}, "displayColor");
    EXPECT_EQ(scene.adopt(stageOf(readerMaterial("Cd") + quad("Quad", -0.5, primvars))),
              2u);
    expectColour(albedoAt(scene.renderAlbedo(), kLeft, kRow), {0.05f, 0.05f, 0.8f}, "Cd after the edit");
}

// The colour AOV's alpha at a pixel: the opacity of a transparent surface over nothing.
float alphaAt(const std::vector<float>& color, int x, int y) { return color.at((size_t(y) * kWidth + size_t(x)) * 4 + 3); }

TEST(PrimvarReaderStage, OpacityReadsEachPrimsDisplayOpacity) {
    HostedStage scene(stageOf(opacityReaderMaterial("displayOpacity") +
            quad("Half", -0.5, "    float[] primvars:displayOpacity = [0.5]\n") +
            quad("Whole", 0.5, "    float[] primvars:displayOpacity = [1]\n")));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.5f, 1.0f / 255.0f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 1.0f, 1.0f / 255.0f);
    EXPECT_FALSE(scene.warned("not supported"));
}

// Opacity of another name, varying over the quad (0.2 at its left edge, 1 at its right), and the
// reader's fallback (unauthored: zero) on a quad without it.
TEST(PrimvarReaderStage, OpacityOfAnyPrimvarOrTheFallback) {
    HostedStage scene(stageOf(opacityReaderMaterial("alpha") +
            quad("Ramp", -0.5,
                 "    float[] primvars:alpha = [0.2, 1, 1, 0.2] (\n        interpolation = \"vertex\"\n    )\n") +
            quad("Without", 0.5, "")));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.6f, 0.02f);
    EXPECT_LT(alphaAt(color, kLeft - 10, kRow), 0.4f);
    EXPECT_GT(alphaAt(color, kLeft + 10, kRow), 0.8f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 0.0f, 1.0f / 255.0f);

    HostedStage withFallback(stageOf(opacityReaderMaterial("alpha", "            float inputs:fallback = 0.3\n") +
            quad("Without", 0.5, "")));
    EXPECT_NEAR(alphaAt(withFallback.renderAov("color", 4), kRight, kRow), 0.3f, 1.0f / 255.0f);
}

// Hydra's instance primvars reach a material whose opacity reads displayOpacity.
TEST(PrimvarReaderStage, InstanceOpacityThroughTheReader) {
    HostedStage scene(stageOf(
        instancedQuads(opacityReaderMaterial("displayOpacity"),
                       "    float[] primvars:displayOpacity = [0.25, 1] (\n        interpolation = \"vertex\"\n    )\n",
                       "    float[] primvars:displayOpacity = [0.6]\n")));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.25f, 1.0f / 255.0f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 1.0f, 1.0f / 255.0f);
}

// The same for opacity read from an instance primvar of another name.
TEST(PrimvarReaderStage, InstanceOpacityThroughAReaderOfAnyName) {
    HostedStage scene(stageOf(
        instancedQuads(opacityReaderMaterial("alpha"),
                       "    float[] primvars:alpha = [0.25, 1] (\n        interpolation = \"vertex\"\n    )\n",
                       "    float[] primvars:alpha = [0.6]\n")));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.25f, 1.0f / 255.0f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 1.0f, 1.0f / 255.0f);
}

// A MaterialX Standard Surface whose `input` (a declaration, "color3f inputs:base_color") is fed
// through a NodeGraph output by an ND_geompropvalue `nodeId` of `geomprop`, with the node's
// `extra` lines (its default) and the surface's `surfaceLines`.
std::string geompropLook(const std::string& input, const std::string& nodeId, const std::string& geomprop,
                         const std::string& extra, const std::string& surfaceLines = "") {
    const std::string type = input.substr(0, input.find(' '));
    return "def Material \"Look\"\n{\n"
           "    token outputs:mtlx:surface.connect = </Look/Surface.outputs:surface>\n"
           "    def Shader \"Surface\"\n    {\n"
           "        uniform token info:id = \"ND_standard_surface_surfaceshader\"\n" + surfaceLines +
           "        " + input + ".connect = </Look/Primvars.outputs:value>\n"
           "        token outputs:surface\n    }\n"
           "    def NodeGraph \"Primvars\"\n    {\n"
           "        " + type + " outputs:value.connect = </Look/Primvars/Node.outputs:out>\n"
           "        def Shader \"Node\"\n        {\n"
           "            uniform token info:id = \"" + nodeId + "\"\n"
           "            string inputs:geomprop = \"" + geomprop + "\"\n" + extra +
           "            " + type + " outputs:out\n        }\n    }\n}\n";
}

// Houdini's vertex colours as Solaris writes them: base_color reads Cd, scaled by Standard
// Surface's base (its default 0.8); a prim without Cd takes the node's default.
TEST(PrimvarReaderStage, MaterialXBaseColourReadsAGeomprop) {
    HostedStage scene(stageOf(
        geompropLook("color3f inputs:base_color", "ND_geompropvalue_color3", "Cd",
                     "            color3f inputs:default = (0.1, 0.6, 0.3)\n") +
        quad("Red", -0.5, "    color3f[] primvars:Cd = [(0.8, 0.05, 0.05)]\n") + quad("Plain", 0.5, "")));
    std::vector<float> albedo = scene.renderAlbedo();
    expectColour(albedoAt(albedo, kLeft, kRow), {0.64f, 0.04f, 0.04f}, "base 0.8 times Cd");
    expectColour(albedoAt(albedo, kRight, kRow), {0.08f, 0.48f, 0.24f}, "base 0.8 times the node's default");
    EXPECT_FALSE(scene.warned("cannot be folded"));
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;

    // An authored base of 0.5: the factor the vertex colour is scaled by.
    HostedStage half(stageOf(geompropLook("color3f inputs:base_color", "ND_geompropvalue_color3", "Cd", "",
                                          "        float inputs:base = 0.5\n") +
                             quad("Red", -0.5, "    color3f[] primvars:Cd = [(0.8, 0.4, 0.2)]\n")));
    expectColour(albedoAt(half.renderAlbedo(), kLeft, kRow), {0.4f, 0.2f, 0.1f}, "base 0.5 times Cd");
}

TEST(PrimvarReaderStage, MaterialXOpacityReadsAGeomprop) {
    HostedStage scene(stageOf(geompropLook("float inputs:opacity", "ND_geompropvalue_float", "alpha", "") +
                              quad("Half", -0.5, "    float[] primvars:alpha = [0.5]\n") +
                              quad("Whole", 0.5, "    float[] primvars:alpha = [1]\n")));
    std::vector<float> color = scene.renderAov("color", 4);
    EXPECT_NEAR(alphaAt(color, kLeft, kRow), 0.5f, 1.0f / 255.0f);
    EXPECT_NEAR(alphaAt(color, kRight, kRow), 1.0f, 1.0f / 255.0f);
}

// Obscura's material model reads primvars into the base colour and the opacity only: a geomprop on
// the roughness is reported, naming the surface and the primvar, and the input keeps its default.
TEST(PrimvarReaderStage, MaterialXGeompropElsewhereIsReported) {
    HostedStage scene(stageOf(geompropLook("float inputs:specular_roughness", "ND_geompropvalue_float", "rough", "") +
                              quad("Quad", -0.5, "    float[] primvars:rough = [0.9]\n")));
    scene.renderAlbedo();
    EXPECT_TRUE(scene.warned("/Look/Surface.inputs:specular_roughness reads primvar rough, and Obscura's material "
                             "model reads primvars on diffuseColor and opacity only; its default is used"));
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
    HostedStage scene(stageOf(material + quad("Quad", -0.5, "    color3f[] primvars:displayColor = [(0.8, 0.05, 0.05)]\n")));
    expectColour(albedoAt(scene.renderAlbedo(), kLeft, kRow), {0.05f, 0.05f, 0.9f}, "material");
}

}  // namespace
}  // namespace obscura::test
