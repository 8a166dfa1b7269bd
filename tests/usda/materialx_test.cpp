// MaterialX documents read as USD layers (as usdMtlx presents them): the Open Chess Set's materials,
// referenced from its look layers, compose into UsdShade Materials whose shaders, node graphs and
// connections are those of the document; a malformed document warns where it is malformed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness/usda/materialx_layer.h"
#include "usda_test_util.h"

namespace obscura::usda::test {
namespace {

namespace fs = std::filesystem;

const fs::path kBishop = fs::path(OBSCURA_CORPUS_DIR) / "full_assets/OpenChessSet/assets/Bishop";

const Attribute& attributeOf(const Stage& stage, const std::string& prim, const std::string& name) {
    static const Attribute missing;
    const Prim* p = stage.find(prim);
    const Attribute* a = p ? p->attribute(name) : nullptr;
    if (!a) ADD_FAILURE() << "no " << prim << "." << name;
    return a ? *a : missing;
}

TEST(MaterialX, TheChessSetsMaterialsComposeAsUsdShade) {
    if (!fs::exists(kBishop)) GTEST_SKIP() << "no corpus at " << kBishop;
    auto stage = openFile((kBishop / "Bishop.usd").string());
    ASSERT_TRUE(stage);
    // Bishop_look.usd: def Scope "Materials" (prepend references = @./Bishop_mat.mtlx@</MaterialX/Materials>).
    const std::string material = "/Bishop/Materials/M_Bishop_B";
    ASSERT_TRUE(stage->find(material));
    EXPECT_EQ(stage->find(material)->typeName, "Material");
    EXPECT_EQ(attributeOf(*stage, material, "outputs:mtlx:surface").connection,
              material + "/Bishop_B.outputs:surface");
    const std::string shader = material + "/Bishop_B";
    EXPECT_EQ(attributeOf(*stage, shader, "info:id").defaultValue->strings.front(), "ND_standard_surface_surfaceshader");
    // <input name="base_color" type="color3" nodegraph="NG_BishopBlack" output="base_color_output" />
    const Attribute& baseColor = attributeOf(*stage, shader, "inputs:base_color");
    EXPECT_EQ(baseColor.typeName, "color3f");
    EXPECT_EQ(baseColor.connection, material + "/NG_BishopBlack.outputs:base_color_output");
    EXPECT_EQ(stage->find(material + "/NG_BishopBlack")->typeName, "NodeGraph");
    EXPECT_EQ(attributeOf(*stage, material + "/NG_BishopBlack", "outputs:base_color_output").connection,
              material + "/NG_BishopBlack/diffuse2.outputs:out");
    // <image name="diffuse2" type="color3"> <input name="file" type="filename"
    //     value="tex/bishop_black_base_color.jpg" colorspace="srgb_texture" />
    const std::string image = material + "/NG_BishopBlack/diffuse2";
    EXPECT_EQ(attributeOf(*stage, image, "info:id").defaultValue->strings.front(), "ND_image_color3");
    const Attribute& file = attributeOf(*stage, image, "inputs:file");
    EXPECT_EQ(file.typeName, "asset");
    EXPECT_EQ(file.defaultValue->strings.front(), "tex/bishop_black_base_color.jpg");
    EXPECT_EQ(file.metadata.at("colorSpace").strings.front(), "srgb_texture");
    EXPECT_EQ(fs::path(file.where.file).filename(), "Bishop_mat.mtlx");
    EXPECT_EQ(file.where.line, 8);
    // <normalmap name="mtlxnormalmap4" type="vector3"> <input name="in" type="vector3" nodename="normal2" />
    EXPECT_EQ(attributeOf(*stage, material + "/NG_BishopBlack/mtlxnormalmap4", "inputs:in").connection,
              material + "/NG_BishopBlack/normal2.outputs:out");
    for (const Warning& warning : stage->warnings())
        EXPECT_EQ(warning.message.find("MaterialX"), std::string::npos) << warning.message;
}

TEST(MaterialX, ValuesAndDocumentLevelNodes) {
    const std::string document = R"(<?xml version="1.0"?>
<materialx version="1.38">
  <constant name="tint" type="color3">
    <input name="value" type="color3" value="0.5, 0.25, 1" />
  </constant>
  <standard_surface name="Surface" type="surfaceshader">
    <input name="base_color" type="color3" nodename="tint" />
    <input name="specular_roughness" type="float" value="0.35" />
  </standard_surface>
  <surfacematerial name="Look" type="material">
    <input name="surfaceshader" type="surfaceshader" nodename="Surface" />
  </surfacematerial>
</materialx>
)";
    auto layer = readMaterialXLayer(document, "looks.mtlx");
    ASSERT_TRUE(std::holds_alternative<std::unique_ptr<Layer>>(layer)) << std::get<Error>(layer).str();
    const Layer& l = *std::get<std::unique_ptr<Layer>>(layer);
    EXPECT_EQ(l.metadata.at("defaultPrim").strings.front(), "MaterialX");
    const PrimSpec* surface = l.find("/MaterialX/Materials/Look/Surface");
    ASSERT_TRUE(surface);
    EXPECT_EQ(surface->attributes.at("inputs:specular_roughness").defaultValue->numbers, std::vector<double>{0.35});
    EXPECT_EQ(surface->attributes.at("inputs:base_color").connections.explicitItems,
              std::vector<std::string>{"/MaterialX/Materials/Look/tint.outputs:out"});
    const PrimSpec* tint = l.find("/MaterialX/Materials/Look/tint");
    ASSERT_TRUE(tint);
    EXPECT_EQ(tint->attributes.at("info:id").defaultValue->strings.front(), "ND_constant_color3");
    EXPECT_EQ(tint->attributes.at("inputs:value").defaultValue->numbers, (std::vector<double>{0.5, 0.25, 1}));
    EXPECT_TRUE(l.diagnostics.empty());
}

TEST(MaterialX, AMalformedDocumentWarnsWhereAndAddsNothing) {
    const fs::path dir = fs::temp_directory_path() / "obscura_materialx_test";
    fs::create_directories(dir);
    std::ofstream(dir / "broken.mtlx") << "<?xml version=\"1.0\"?>\n<materialx>\n  <nodegraph name=\"x\">\n</materialx>\n";
    std::ofstream(dir / "scene.usda") << "#usda 1.0\ndef Scope \"Looks\" (references = @broken.mtlx@</MaterialX/Materials>)\n{\n}\n";
    auto stage = openFile((dir / "scene.usda").string());
    ASSERT_TRUE(stage);
    ASSERT_EQ(stage->warnings().size(), 1u);
    const Warning& warning = stage->warnings().front();
    // At the arc, with where the document goes wrong.
    EXPECT_EQ(warning.message.find("reference of </Looks> to @broken.mtlx@ ignored: " + (dir / "broken.mtlx").string() +
                                   ":4:"),
              0u)
        << warning.message;
    EXPECT_NE(warning.message.find("not well-formed XML"), std::string::npos) << warning.message;
    EXPECT_EQ(fs::path(warning.where.file).filename(), "scene.usda");
    EXPECT_EQ(warning.where.line, 2);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace obscura::usda::test
