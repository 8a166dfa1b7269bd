// Omniverse's OmniPBR MDL materials (harness/omni_pbr_surface.h) mapped onto Obscura's material
// model through the scene host: constants with OmniPBR's formulas and defaults, textures with
// their colour spaces, influences and placement, the ORM texture; a material with an MDL surface
// alone is drawn; another MDL material falls back to its base colour with one warning.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace obscura::test {
namespace {

// A Material whose outputs:mdl:surface is the OmniPBR shader with `inputs` (whole lines).
std::string omniPbr(const std::string& name, const std::string& inputs) {
    return "def Material \"" + name + "\"\n{\n"
           "    token outputs:mdl:surface.connect = </" + name + "/Shader.outputs:out>\n"
           "    def Shader \"Shader\"\n    {\n"
           "        uniform token info:implementationSource = \"sourceAsset\"\n"
           "        uniform asset info:mdl:sourceAsset = @OmniPBR.mdl@\n"
           "        uniform token info:mdl:sourceAsset:subIdentifier = \"OmniPBR\"\n" + inputs +
           "        token outputs:out\n    }\n}\n";
}

HostedStage stageOf(const std::string& body) {
    return HostedStage(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + body, OBSCURA_TEST_DATA_DIR "/omni.usda"));
}

void expectFloats(const std::vector<float>& actual, const std::vector<float>& expected, const char* what) {
    ASSERT_EQ(actual.size(), expected.size()) << what;
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(actual[i], expected[i], 1e-5) << what << " [" << i << "]";
}

TEST(OmniPbrSurface, ConstantsMapWithOmniPbrsFormulas) {
    HostedStage scene = stageOf(omniPbr("Plain", "") +
                                omniPbr("Tuned", R"(        color3f inputs:diffuse_color_constant = (0.5, 0.4, 0.3)
        color3f inputs:diffuse_tint = (1, 0.5, 1)
        float inputs:albedo_brightness = 0.1
        float inputs:reflection_roughness_constant = 0.3
        float inputs:metallic_constant = 0.7
        float inputs:specular_level = 1
        bool inputs:enable_emission = 1
        color3f inputs:emissive_color = (1, 0.5, 0)
        float inputs:emissive_intensity = 2
        bool inputs:enable_opacity = 1
        float inputs:opacity_constant = 0.4
        float inputs:opacity_threshold = 0.2
)"));
    // OmniPBR's defaults.
    expectFloats(scene.floats("/Plain", "inputs:diffuseColor"), {0.2f, 0.2f, 0.2f}, "diffuse default");
    expectFloats(scene.floats("/Plain", "inputs:roughness"), {0.5f}, "roughness default");
    expectFloats(scene.floats("/Plain", "inputs:metallic"), {0.0f}, "metallic default");
    expectFloats(scene.floats("/Plain", "inputs:ior"), {1.5f}, "specular_level 0.5: F0 0.04");
    EXPECT_FALSE(scene.served("/Plain", "inputs:emissiveColor"));  // emission off
    EXPECT_FALSE(scene.served("/Plain", "inputs:opacity"));         // opacity off
    // The tint multiplies; brightness acts on a texture only.
    expectFloats(scene.floats("/Tuned", "inputs:diffuseColor"), {0.5f, 0.2f, 0.3f}, "constant times tint");
    expectFloats(scene.floats("/Tuned", "inputs:roughness"), {0.3f}, "roughness");
    expectFloats(scene.floats("/Tuned", "inputs:metallic"), {0.7f}, "metallic");
    // specular_level 1: F0 = 0.08, ior = (1 + sqrt F0) / (1 - sqrt F0).
    const float ior = float((1 + std::sqrt(0.08)) / (1 - std::sqrt(0.08)));
    expectFloats(scene.floats("/Tuned", "inputs:ior"), {ior}, "ior of specular_level 1");
    expectFloats(scene.floats("/Tuned", "inputs:emissiveColor"), {2.0f, 1.0f, 0.0f}, "colour times intensity");
    expectFloats(scene.floats("/Tuned", "inputs:opacity"), {0.4f}, "opacity");
    expectFloats(scene.floats("/Tuned", "inputs:opacityThreshold"), {0.2f}, "threshold");
    EXPECT_EQ(scene.messagesWith("OmniPBR"), 0u);
}

TEST(OmniPbrSurface, TexturesWithTheirInfluenceAndPlacement) {
    HostedStage scene = stageOf(omniPbr("Textured", R"(        asset inputs:diffuse_texture = @textures/checker.png@ (
            colorSpace = "sRGB"
        )
        float inputs:albedo_brightness = 0.5
        float inputs:albedo_add = 0.1
        color3f inputs:diffuse_tint = (1, 1, 0.5)
        asset inputs:reflectionroughness_texture = @textures/checker.png@
        float inputs:reflection_roughness_constant = 0.8
        float inputs:reflection_roughness_texture_influence = 0.25
        asset inputs:metallic_texture = @textures/checker.png@
        asset inputs:normalmap_texture = @textures/checker.png@
        float2 inputs:texture_scale = (2, 2)
        float inputs:texture_rotate = 90
        float2 inputs:texture_translate = (0.5, 0)
)") + omniPbr("Orm", R"(        bool inputs:enable_ORM_texture = 1
        asset inputs:ORM_texture = @textures/checker.png@
)"));
    const std::filesystem::path checker = OBSCURA_TEST_DATA_DIR "/textures/checker.png";
    EXPECT_EQ(std::filesystem::path(scene.token("/Textured", "obscura:diffuseColor:file")), checker);
    EXPECT_EQ(scene.token("/Textured", "obscura:diffuseColor:sourceColorSpace"), "sRGB");
    // texel x brightness + add, times the tint.
    expectFloats(scene.floats("/Textured", "obscura:diffuseColor:scale"), {0.5f, 0.5f, 0.25f, 1}, "diffuse scale");
    expectFloats(scene.floats("/Textured", "obscura:diffuseColor:bias"), {0.1f, 0.1f, 0.05f, 0}, "diffuse bias");
    // Scaled by 2, turned a quarter turn, moved by (0.5, 0): s' = 0.5 - 2t, t' = 2s.
    expectFloats(scene.floats("/Textured", "obscura:diffuseColor:transformS"), {0, -2, 0.5f}, "placement s");
    expectFloats(scene.floats("/Textured", "obscura:diffuseColor:transformT"), {2, 0, 0}, "placement t");
    // lerp(0.8, texel, 0.25), read as data.
    expectFloats(scene.floats("/Textured", "obscura:roughness:scale"), {0.25f, 0.25f, 0.25f, 1}, "roughness scale");
    expectFloats(scene.floats("/Textured", "obscura:roughness:bias"), {0.6f, 0.6f, 0.6f, 0}, "roughness bias");
    EXPECT_EQ(scene.token("/Textured", "obscura:roughness:sourceColorSpace"), "raw");
    // The metallic texture's influence is 0 by default: the constant.
    EXPECT_FALSE(scene.served("/Textured", "obscura:metallic:file"));
    expectFloats(scene.floats("/Textured", "inputs:metallic"), {0.0f}, "metallic");
    expectFloats(scene.floats("/Textured", "obscura:normal:scale"), {2, 2, 2, 1}, "normal map decoding");
    expectFloats(scene.floats("/Textured", "obscura:normal:bias"), {-1, -1, -1, 0}, "normal map decoding");
    // ORM: occlusion, roughness and metallic in r, g and b.
    EXPECT_EQ(scene.token("/Orm", "obscura:occlusion:channel"), "r");
    EXPECT_EQ(scene.token("/Orm", "obscura:roughness:channel"), "g");
    EXPECT_EQ(scene.token("/Orm", "obscura:metallic:channel"), "b");
    EXPECT_EQ(scene.messagesWith("OmniPBR"), 0u);
}

// A mesh bound to a material with an MDL surface alone, as Omniverse writes them: drawn with the
// OmniPBR colour (before, the material was skipped and the mesh drawn grey).
TEST(OmniPbrSurface, AnMdlOnlyMaterialIsDrawn) {
    HostedStage scene = stageOf(omniPbr("Red", "        color3f inputs:diffuse_color_constant = (0.8, 0.1, 0.1)\n") + R"(
def Mesh "Quad" (
    prepend apiSchemas = ["MaterialBindingAPI"]
)
{
    point3f[] points = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    rel material:binding = </Red>
}
)");
    std::vector<float> albedo = scene.renderAlbedo();
    const size_t centre = (size_t(32) * kWidth + 32) * 3;
    EXPECT_NEAR(albedo.at(centre), 0.8f, 0.01f);
    EXPECT_NEAR(albedo.at(centre + 1), 0.1f, 0.01f);
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
}

// Another MDL material: its base colour, under the names MDL materials use, with one warning
// naming the module's material.
TEST(OmniPbrSurface, OtherMdlMaterialsFallBackToTheirBaseColour) {
    HostedStage scene = stageOf(R"(def Material "Surface"
{
    token outputs:mdl:surface.connect = </Surface/Shader.outputs:out>
    def Shader "Shader"
    {
        uniform token info:implementationSource = "sourceAsset"
        uniform asset info:mdl:sourceAsset = @OmniSurface.mdl@
        uniform token info:mdl:sourceAsset:subIdentifier = "OmniSurface"
        color3f inputs:diffuse_reflection_color = (0.3, 0.6, 0.9)
        token outputs:out
    }
}
)");
    expectFloats(scene.floats("/Surface", "inputs:diffuseColor"), {0.3f, 0.6f, 0.9f}, "base colour");
    EXPECT_EQ(scene.messagesWith("/Surface/Shader (MDL OmniSurface) is not a surface Obscura's material model maps"), 1u);
}

}  // namespace
}  // namespace obscura::test
