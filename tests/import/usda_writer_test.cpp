// The USD text writer: what it writes reads back through the harness's parser unchanged.
#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <variant>

#include "harness/import/usda_writer.h"
#include "harness/usda/stage.h"

namespace obscura::harness::importer {
namespace {

std::unique_ptr<usda::Stage> parse(const UsdaWriter& out) {
    auto result = usda::Stage::openFromString(out.text(), "/virtual/writer.usda");
    if (const usda::Error* error = std::get_if<usda::Error>(&result)) {
        ADD_FAILURE() << error->str() << "\n" << out.text();
        return nullptr;
    }
    return std::get<std::unique_ptr<usda::Stage>>(std::move(result));
}

TEST(UsdaWriter, NumbersAreShortestAndReadBackExactly) {
    EXPECT_EQ(number(0.1f), "0.1");
    EXPECT_EQ(number(1.0f), "1");
    EXPECT_EQ(number(-0.0f), "0");
    EXPECT_EQ(number(0.0254), "0.0254");
    for (const float value : {0.1f, 1e-7f, 3.4e38f, -123.456f, std::numeric_limits<float>::min()})
        EXPECT_EQ(std::strtof(number(value).c_str(), nullptr), value) << number(value);
}

TEST(UsdaWriter, DocumentReadsBack) {
    UsdaWriter out({"defaultPrim = \"A\"", "metersPerUnit = 0.01"});
    out.beginPrim("Xform", "A");
    out.beginPrim("Mesh", "M", {"prepend apiSchemas = [\"MaterialBindingAPI\"]"});
    out.property("point3f[] points", array(2, [](size_t i) { return tuple({float(i), 0.5f, -2e-5f}); }));
    out.vertexProperty("texCoord2f[] primvars:st", "[(0, 1), (1, 0)]");
    out.property("rel material:binding", pathRef("/A/Looks/X"));
    out.declare("token outputs:surface");
    out.endPrim();
    out.timeSamples("float3 xformOp:translate", {{0, tuple({1, 2, 3})}, {24, tuple({4, 5, 6})}});
    out.property("matrix4d xformOp:transform", matrix({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 7, 8, 9, 1}));
    out.endPrim();

    const auto stage = parse(out);
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->metadata().metersPerUnit, 0.01);
    const usda::Prim* mesh = stage->find("/A/M");
    ASSERT_TRUE(mesh);
    EXPECT_EQ(mesh->apiSchemas, std::vector<std::string>{"MaterialBindingAPI"});
    const std::vector<double>& points = mesh->attribute("points")->defaultValue->numbers;
    ASSERT_EQ(points.size(), 6u);
    EXPECT_EQ(points[3], 1);
    EXPECT_EQ(static_cast<float>(points[5]), -2e-5f);
    EXPECT_EQ(mesh->attribute("primvars:st")->metadata.at("interpolation").strings.front(), "vertex");
    EXPECT_EQ(mesh->relationship("material:binding")->targets, std::vector<std::string>{"/A/Looks/X"});
    EXPECT_TRUE(mesh->attribute("outputs:surface"));
    const usda::Attribute* translate = stage->find("/A")->attribute("xformOp:translate");
    ASSERT_EQ(translate->timeSamples.size(), 2u);
    EXPECT_EQ(translate->evaluate(12)->numbers, (std::vector<double>{2.5, 3.5, 4.5}));
    EXPECT_EQ(stage->find("/A")->attribute("xformOp:transform")->defaultValue->numbers.at(12), 7);
}

TEST(UsdaWriter, StringsAndAssetPathsReadBack) {
    const std::string text = "say \"hi\"\\ then\ttab\nnewline";
    const std::string plain = "/textures/wall.png";
    const std::string ats = "/t/a@b@@@c.png";
    UsdaWriter out({"doc = " + stringLiteral(text)});
    out.beginPrim("Shader", "S");
    out.property("asset inputs:plain", *assetPath(plain));
    out.property("asset inputs:ats", *assetPath(ats));
    out.endPrim();

    const auto stage = parse(out);
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->metadata().doc, text);
    EXPECT_EQ(stage->find("/S")->attribute("inputs:plain")->defaultValue->strings.front(), plain);
    EXPECT_EQ(stage->find("/S")->attribute("inputs:ats")->defaultValue->strings.front(), ats);
    EXPECT_FALSE(assetPath("a\nb.png"));
}

TEST(NameScope, NamesBecomeUniqueIdentifiers) {
    NameScope names;
    EXPECT_EQ(names.claim("Root Group", "Node"), "Root_Group");
    EXPECT_EQ(names.claim("mesh-0.001", "Node"), "mesh_0_001");
    EXPECT_EQ(names.claim("3D", "Node"), "_3D");
    EXPECT_EQ(names.claim("", "Node"), "Node");
    EXPECT_EQ(names.claim("\xc3\xa9t\xc3\xa9", "Node"), "_t_");
    EXPECT_EQ(names.claim("$$$", "Node"), "Node_1");
    EXPECT_EQ(names.claim("Root_Group", "Node"), "Root_Group_1");
    EXPECT_EQ(names.claim("Root Group", "Node"), "Root_Group_2");
    NameScope other;
    EXPECT_EQ(other.claim("Root Group", "Node"), "Root_Group");
}

}  // namespace
}  // namespace obscura::harness::importer
