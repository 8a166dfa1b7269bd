// MaterialX surfaces mapped onto Obscura's material model through the harness's scene host: a
// MaterialX document's image node textures a plane as a UsdPreviewSurface texture does
// (tests/harness/data/textured_materialx.usda, the four colour blocks of textured.usda); networks
// authored in UsdShade fold into textures with scale and bias or into constants, each surface model
// with its own defaults; what cannot map is reported once, naming the node, and falls back.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace obscura::test {
namespace {

TEST(MaterialXSurface, AnImageNodeTexturesThePlaneAsUsdUVTextureDoes) {
    HostedStage scene(usda::Stage::open(OBSCURA_TEST_DATA_DIR "/textured_materialx.usda"));
    scene.setBool("textures:compression", false);  // the blocks' exact codes, not BC1's 5:6:5 endpoints
    auto albedo = scene.renderAlbedo();
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
    // base 1 times the sRGB-encoded blocks, decoded (colorspace srgb_texture).
    auto expect = [&](int x, int y, std::array<int, 3> codes, const char* what) {
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(albedo.at((size_t(y) * kWidth + size_t(x)) * 3 + c), srgb8Exact(codes[c]), 0.004f)
                << what << " channel " << c;
    };
    expect(16, 16, {200, 40, 40}, "top left");
    expect(48, 16, {40, 200, 40}, "top right");
    expect(16, 48, {40, 40, 200}, "bottom left");
    expect(48, 48, {220, 220, 60}, "bottom right");
}

const char* kNetworks = R"(#usda 1.0
def Material "Standard"
{
    token outputs:mtlx:surface.connect = </Standard/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "ND_standard_surface_surfaceshader"
        float inputs:base = 0.5
        color3f inputs:base_color.connect = </Standard/Graph.outputs:color>
        float inputs:metalness.connect = </Standard/Graph.outputs:metal>
        float inputs:specular_roughness = 0.35
        float inputs:specular_anisotropy = 0.6
        float inputs:specular_rotation = 0.125
        float3 inputs:normal.connect = </Standard/Graph.outputs:normal>
        token outputs:surface
    }
    def NodeGraph "Graph"
    {
        color3f outputs:color.connect = </Standard/Graph/Tint.outputs:out>
        float outputs:metal.connect = </Standard/Graph/Metal.outputs:out>
        float3 outputs:normal.connect = </Standard/Graph/NormalMap.outputs:out>
        def Shader "Coords"
        {
            uniform token info:id = "ND_geompropvalue_vector2"
            string inputs:geomprop = "uv1"
            float2 outputs:out
        }
        def Shader "Image"
        {
            uniform token info:id = "ND_image_color3"
            asset inputs:file = @textures/checker.png@ (
                colorSpace = "srgb_texture"
            )
            string inputs:uaddressmode = "clamp"
            float2 inputs:texcoord.connect = </Standard/Graph/Coords.outputs:out>
            color3f outputs:out
        }
        def Shader "Tint"
        {
            uniform token info:id = "ND_multiply_color3"
            color3f inputs:in1.connect = </Standard/Graph/Image.outputs:out>
            color3f inputs:in2 = (1, 0.5, 0.25)
            color3f outputs:out
        }
        def Shader "Metal"
        {
            uniform token info:id = "ND_mix_float"
            float inputs:fg = 1
            float inputs:bg = 0
            float inputs:mix = 0.25
            float outputs:out
        }
        def Shader "NormalImage"
        {
            uniform token info:id = "ND_image_vector3"
            asset inputs:file = @textures/checker.png@
            float3 outputs:out
        }
        def Shader "NormalMap"
        {
            uniform token info:id = "ND_normalmap"
            float3 inputs:in.connect = </Standard/Graph/NormalImage.outputs:out>
            float3 outputs:out
        }
    }
}
def Material "Gltf"
{
    token outputs:surface.connect = </Gltf/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "ND_gltf_pbr_surfaceshader"
        color3f inputs:base_color = (0.2, 0.4, 0.6)
        int inputs:alpha_mode = 1
        float inputs:alpha = 0.3
        float inputs:alpha_cutoff = 0.6
        token outputs:surface
    }
}
def Material "OpenPbr"
{
    token outputs:surface.connect = </OpenPbr/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "ND_open_pbr_surface_surfaceshader"
        float inputs:base_weight = 0.5
        color3f inputs:base_color = (1, 1, 0)
        token outputs:surface
    }
}
def Material "Preview"
{
    token outputs:surface.connect = </Preview/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "ND_UsdPreviewSurface_surfaceshader"
        color3f inputs:diffuseColor = (0.1, 0.2, 0.3)
        float inputs:roughness = 0.7
        float inputs:metallic = 0.4
        color3f inputs:emissiveColor = (0.5, 0.25, 0.125)
        float inputs:opacity = 0.6
        token outputs:surface
    }
}
def Material "Unfoldable"
{
    token outputs:surface.connect = </Unfoldable/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "ND_standard_surface_surfaceshader"
        color3f inputs:base_color.connect = </Unfoldable/Product.outputs:out>
        token outputs:surface
    }
    def Shader "Image"
    {
        uniform token info:id = "ND_image_color3"
        asset inputs:file = @textures/checker.png@
        color3f outputs:out
    }
    def Shader "Product"
    {
        uniform token info:id = "ND_multiply_color3"
        color3f inputs:in1.connect = </Unfoldable/Image.outputs:out>
        color3f inputs:in2.connect = </Unfoldable/Image.outputs:out>
        color3f outputs:out
    }
}
def Material "Foreign"
{
    token outputs:surface.connect = </Foreign/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "PxrSurface"
        color3f inputs:diffuseColor = (0.3, 0.2, 0.1)
        token outputs:surface
    }
}
def Mesh "Quad"
{
    point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    texCoord2f[] primvars:uv1 = [(0, 0), (1, 0), (1, 1), (0, 1)] (
        interpolation = "vertex"
    )
    rel material:binding = </Standard>
}
)";

// The networks above through the scene host.
struct Networks : HostedStage {
    explicit Networks(std::variant<std::unique_ptr<usda::Stage>, usda::Error> opened =
                          usda::Stage::openFromString(kNetworks, OBSCURA_TEST_DATA_DIR "/networks.usda"))
        : HostedStage(std::move(opened)) {}
};

void expectFloats(const std::vector<float>& actual, const std::vector<float>& expected, const char* what) {
    ASSERT_EQ(actual.size(), expected.size()) << what;
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(actual[i], expected[i], 1e-6) << what << " [" << i << "]";
}

TEST(MaterialXSurface, StandardSurfaceNetworksFoldIntoTexturesAndConstants) {
    Networks n;
    // base 0.5 times (image times (1, 0.5, 0.25)): the image scaled.
    const std::string file = n.token("/Standard", "obscura:diffuseColor:file");
    EXPECT_EQ(std::filesystem::path(file), std::filesystem::path(OBSCURA_TEST_DATA_DIR "/textures/checker.png"));
    expectFloats(n.floats("/Standard", "obscura:diffuseColor:scale"), {0.5f, 0.25f, 0.125f, 1.0f}, "diffuse scale");
    expectFloats(n.floats("/Standard", "obscura:diffuseColor:bias"), {0, 0, 0, 0}, "diffuse bias");
    EXPECT_EQ(n.token("/Standard", "obscura:diffuseColor:sourceColorSpace"), "sRGB");
    EXPECT_EQ(n.token("/Standard", "obscura:diffuseColor:wrapS"), "clamp");
    EXPECT_EQ(n.token("/Standard", "obscura:diffuseColor:wrapT"), "repeat");  // MaterialX's periodic default
    EXPECT_EQ(n.token("/Standard", "obscura:diffuseColor:st"), "uv1");
    // mix(fg 1, bg 0, mix 0.25) = 0.25.
    expectFloats(n.floats("/Standard", "inputs:metallic"), {0.25f}, "metallic");
    expectFloats(n.floats("/Standard", "inputs:roughness"), {0.35f}, "roughness");
    // The anisotropic lobe: specular_rotation is a fraction of a turn, obscura:anisotropyRotation degrees.
    expectFloats(n.floats("/Standard", "inputs:obscura:anisotropy"), {0.6f}, "specular_anisotropy");
    expectFloats(n.floats("/Standard", "inputs:obscura:anisotropyRotation"), {45.0f}, "specular_rotation");
    // A normal map decodes n * 2 - 1, from data read as it is.
    expectFloats(n.floats("/Standard", "obscura:normal:scale"), {2, 2, 2, 1}, "normal scale");
    expectFloats(n.floats("/Standard", "obscura:normal:bias"), {-1, -1, -1, 0}, "normal bias");
    EXPECT_EQ(n.token("/Standard", "obscura:normal:sourceColorSpace"), "raw");
    // Standard Surface's own defaults, not UsdPreviewSurface's.
    expectFloats(n.floats("/Standard", "inputs:clearcoatRoughness"), {0.1f}, "coat_roughness default");
    // The mesh's texture coordinates are the primvar the image reads.
    expectFloats(n.floats("/Quad", "primvars:st"), {0, 0, 1, 0, 1, 1, 0, 1}, "primvars:uv1 as st");
    EXPECT_EQ(n.messagesWith("/Standard"), 0u);
}

TEST(MaterialXSurface, GltfAndOpenPbrSurfacesMapWithTheirDefaults) {
    Networks n;
    expectFloats(n.floats("/Gltf", "inputs:diffuseColor"), {0.2f, 0.4f, 0.6f}, "glTF base_color");
    expectFloats(n.floats("/Gltf", "inputs:metallic"), {1}, "glTF metallic default");
    expectFloats(n.floats("/Gltf", "inputs:roughness"), {1}, "glTF roughness default");
    // alpha_mode MASK: cut out below alpha_cutoff.
    expectFloats(n.floats("/Gltf", "inputs:opacity"), {0.3f}, "alpha");
    expectFloats(n.floats("/Gltf", "inputs:opacityThreshold"), {0.6f}, "alpha_cutoff");
    expectFloats(n.floats("/OpenPbr", "inputs:diffuseColor"), {0.5f, 0.5f, 0}, "base_weight * base_color");
    expectFloats(n.floats("/OpenPbr", "inputs:roughness"), {0.3f}, "OpenPBR specular_roughness default");
}

// MaterialX's own UsdPreviewSurface node: each input lands on the UsdPreviewSurface input of its
// name (the values differ, so no two may trade places), and what it leaves out takes
// UsdPreviewSurface's defaults rather than another model's.
TEST(MaterialXSurface, UsdPreviewSurfaceNodeMapsEachInputToItsNamesake) {
    Networks n;
    expectFloats(n.floats("/Preview", "inputs:diffuseColor"), {0.1f, 0.2f, 0.3f}, "diffuseColor");
    expectFloats(n.floats("/Preview", "inputs:roughness"), {0.7f}, "roughness");
    expectFloats(n.floats("/Preview", "inputs:metallic"), {0.4f}, "metallic");
    expectFloats(n.floats("/Preview", "inputs:emissiveColor"), {0.5f, 0.25f, 0.125f}, "emissiveColor");
    expectFloats(n.floats("/Preview", "inputs:opacity"), {0.6f}, "opacity");
    expectFloats(n.floats("/Preview", "inputs:clearcoatRoughness"), {0.01f}, "UsdPreviewSurface's clearcoatRoughness");
    EXPECT_EQ(n.messagesWith("/Preview"), 0u);
}

TEST(MaterialXSurface, WhatCannotMapIsReportedOnceAndFallsBack) {
    Networks n;
    // A product of two textures is no texture: one message naming the node; the input falls
    // back to the model's default (base 0.8 of white).
    EXPECT_EQ(n.messagesWith("/Unfoldable/Product (ND_multiply_color3) cannot be folded"), 1u);
    EXPECT_FALSE(n.served("/Unfoldable", "obscura:diffuseColor:file"));
    expectFloats(n.floats("/Unfoldable", "inputs:diffuseColor"), {0.8f, 0.8f, 0.8f}, "fallback");
    // A surface of no known kind is drawn with its base colour.
    EXPECT_EQ(n.messagesWith("/Foreign/Surface (PxrSurface) is not a surface Obscura's material model maps; drawn "
                             "with its base colour"),
              1u);
    expectFloats(n.floats("/Foreign", "inputs:diffuseColor"), {0.3f, 0.2f, 0.1f}, "base colour");
    // Pulled again: no new message.
    n.floats("/Unfoldable", "inputs:diffuseColor");
    EXPECT_EQ(n.messagesWith("cannot be folded"), 1u);
}

// The Open Chess Set's pieces (shared/corpus): their looks reference MaterialX documents whose
// Standard Surfaces read base colour, metalness, roughness and normal maps from image node graphs.
TEST(MaterialXSurface, TheChessSetsPiecesAreTextured) {
    const std::filesystem::path bishop =
        std::filesystem::path(OBSCURA_CORPUS_DIR) / "full_assets/OpenChessSet/assets/Bishop/Bishop.usd";
    if (!std::filesystem::exists(bishop)) GTEST_SKIP() << "no corpus at " << bishop;
    Networks n(usda::Stage::open(bishop));
    const std::string material = "/Bishop/Materials/M_Bishop_B";
    const std::filesystem::path tex = bishop.parent_path() / "tex";
    auto file = [&](const char* name) { return (tex / name).lexically_normal().string(); };
    EXPECT_EQ(n.token(material, "obscura:diffuseColor:file"), file("bishop_black_base_color.jpg"));
    EXPECT_EQ(n.token(material, "obscura:diffuseColor:sourceColorSpace"), "sRGB");  // colorspace="srgb_texture"
    EXPECT_EQ(n.token(material, "obscura:metallic:file"), file("bishop_shared_metallic.jpg"));
    EXPECT_EQ(n.token(material, "obscura:metallic:channel"), "r");
    EXPECT_EQ(n.token(material, "obscura:roughness:file"), file("bishop_black_roughness.jpg"));
    EXPECT_EQ(n.token(material, "obscura:normal:file"), file("bishop_black_normal.jpg"));
    expectFloats(n.floats(material, "obscura:normal:scale"), {2, 2, 2, 1}, "normal map decoding");
    expectFloats(n.floats(material, "obscura:normal:bias"), {-1, -1, -1, 0}, "normal map decoding");
    // Standard Surface's base of 0.8 scales the base colour texture.
    expectFloats(n.floats(material, "obscura:diffuseColor:scale"), {0.8f, 0.8f, 0.8f, 1}, "base");
    EXPECT_TRUE(n.errors.empty()) << n.errors.front();
}

// An animated MaterialX network re-syncs: the colour reaches the surface's base_color directly, or
// through a multiply node whose second input is sampled; each frame's albedo follows the samples
// (base 1: albedo = base_color; sRGB codes 200 then 40, linear 0.577581 and 0.021219).
TEST(MaterialXSurface, AnAnimatedNetworkRendersEachFramesColour) {
    const std::string camera = "#usda 1.0\n" + usdaCamera() + R"(def Mesh "Plane"
{
    point3f[] points = [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    uniform token subdivisionScheme = "none"
    rel material:binding = </M>
}
def Material "M"
{
    token outputs:mtlx:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "ND_standard_surface_surfaceshader"
        float inputs:base = 1
        float inputs:specular = 0
        token outputs:surface
)";
    const std::string samples = "{ 0: (0.577581, 0.577581, 0.577581), 1: (0.021219, 0.021219, 0.021219) }";
    const std::string direct = "        color3f inputs:base_color.timeSamples = " + samples + "\n    }\n}\n";
    const std::string throughNode = R"(        color3f inputs:base_color.connect = </M/Tint.outputs:out>
    }
    def Shader "Tint"
    {
        uniform token info:id = "ND_multiply_color3"
        color3f inputs:in1 = (1, 1, 1)
        color3f inputs:in2.timeSamples = )" + samples + R"(
        color3f outputs:out
    }
}
)";
    for (const std::string& network : {direct, throughNode}) {
        HostedStage scene(usda::Stage::openFromString(camera + network, OBSCURA_TEST_DATA_DIR "/animated_materialx.usda"));
        auto first = scene.renderAov("albedo", 3, 0.0);
        ASSERT_EQ(first.size(), size_t(kWidth) * kHeight * 3);
        ASSERT_EQ(scene.host->markTimeVarying(scene.api(), scene.delegate), OBSCURA_OK);
        auto second = scene.renderAov("albedo", 3, 1.0);
        ASSERT_EQ(second.size(), size_t(kWidth) * kHeight * 3);
        const size_t centre = (size_t(kHeight / 2) * kWidth + size_t(kWidth / 2)) * 3;
        for (size_t c = 0; c < 3; ++c) {
            EXPECT_NEAR(first.at(centre + c), srgb8Exact(200), 0.004f) << "time 0, channel " << c << "\n" << network;
            EXPECT_NEAR(second.at(centre + c), srgb8Exact(40), 0.004f) << "time 1, channel " << c << "\n" << network;
        }
        EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
        EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
    }
}

}  // namespace
}  // namespace obscura::test
