// Relocates authored in a referenced asset's layer stack: they are part of that stack's
// composition, so they move prims within the asset's namespace and that namespace is mapped
// through the reference (USD glossary, "Relocates"). The referencing stage sees the relocated prim
// at the mapped target with every opinion on it, and nothing at the source.
#include <filesystem>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

const char* kRig = R"(#usda 1.0
(
    defaultPrim = "Rig"
)
def "Rig"
{
    def "Arm"
    {
        double x = 1
        def "Hand"
        {
            double y = 2
        }
    }
}
)";

// The character asset moves the arm its rig brings from Rig/Arm to Arm; `targetOpinion` says
// something about the arm at its new place.
std::string character(const std::string& relocates, bool targetOpinion) {
    return R"(#usda 1.0
(
    defaultPrim = "Char"
)
def "Char" (
)" + relocates + R"()
{
    def "Rig" (
        references = @rig.usda@
    )
    {
    }
)" + (targetOpinion ? "    over \"Arm\"\n    {\n        double z = 3\n    }\n" : "") +
           "}\n";
}

const char* kShot = R"(#usda 1.0
def "World"
{
    def "Hero" (
        references = @char.usda@
    )
    {
    }
    def "Extra" (
        references = @char.usda@
    )
    {
        over "Arm"
        {
            double z = 5
        }
    }
}
)";

double numberOf(const Stage& stage, const std::string& prim, const std::string& attribute) {
    const Value value = test::defaultOf(stage, prim, attribute);
    return value.numbers.empty() ? -1 : value.numbers.front();
}

TEST(AssetRelocates, ARelocateInAReferencedAssetAppliesUnderTheReferencingPath) {
    test::LayerFiles layers({{"rig.usda", kRig},
                             {"char.usda", character("    relocates = {\n        <Rig/Arm>: <Arm>\n    }\n", true)},
                             {"root.usda", kShot}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->find("/World/Hero/Rig"));
    EXPECT_FALSE(stage->find("/World/Hero/Rig/Arm")) << "the source stays empty";
    ASSERT_TRUE(stage->find("/World/Hero/Arm"));
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Arm", "x"), 1);  // the rig's, brought by the asset's reference
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Arm", "z"), 3);  // the asset's own, at the target
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Arm/Hand", "y"), 2);
    // A second reference of the same asset gets its own relocated arm, and the referencing layer's
    // opinion on the target beats the asset's.
    EXPECT_FALSE(stage->find("/World/Extra/Rig/Arm"));
    EXPECT_EQ(numberOf(*stage, "/World/Extra/Arm", "x"), 1);
    EXPECT_EQ(numberOf(*stage, "/World/Extra/Arm", "z"), 5);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
}

TEST(AssetRelocates, ATargetWithoutOpinionsInTheAssetStillHoldsTheMovedPrim) {
    test::LayerFiles layers({{"rig.usda", kRig},
                             {"char.usda", character("    relocates = {\n        <Rig/Arm>: <Arm>\n    }\n", false)},
                             {"root.usda", kShot}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/World/Hero/Rig/Arm"));
    ASSERT_TRUE(stage->find("/World/Hero/Arm"));
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Arm", "x"), 1);
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Arm/Hand", "y"), 2);
}

TEST(AssetRelocates, TheAssetsLayerMetadataRelocatesMapThroughTheReference) {
    std::string asset = character("", true);
    asset.replace(asset.find("    defaultPrim"), 0, "    relocates = {\n        </Char/Rig/Arm>: </Char/Arm>\n    }\n");
    test::LayerFiles layers({{"rig.usda", kRig}, {"char.usda", asset}, {"root.usda", kShot}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/World/Hero/Rig/Arm"));
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Arm", "x"), 1);
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Arm", "z"), 3);
}

TEST(AssetRelocates, ABadRelocateInsideAnAssetWarnsWhereItIsAuthored) {
    // The source inside its own target would repeat namespace forever: reported, and the rig's
    // arm stays where it is.
    test::LayerFiles layers({{"rig.usda", kRig},
                             {"char.usda", character("    relocates = {\n        <Rig>: <Rig/Arm/Rig>\n    }\n", false)},
                             {"root.usda", kShot}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Rig/Arm", "x"), 1);
    ASSERT_EQ(stage->warnings().size(), 1u);
    const Warning& warning = stage->warnings().front();
    EXPECT_NE(warning.message.find("inside itself"), std::string::npos) << warning.message;
    EXPECT_EQ(std::filesystem::path(warning.where.file).filename(), "char.usda");
    EXPECT_EQ(warning.where.line, 5);  // def "Char" (
    EXPECT_GT(warning.where.column, 0);
}

TEST(AssetRelocates, ARootPrimCannotBeATarget) {
    // No arc can bring a root prim, so Pcp rejects relocating to or from one.
    test::LayerFiles layers({{"rig.usda", kRig},
                             {"char.usda", character("    relocates = {\n        <Rig/Arm>: </Arm>\n    }\n", false)},
                             {"root.usda", kShot}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(numberOf(*stage, "/World/Hero/Rig/Arm", "x"), 1);
    EXPECT_FALSE(stage->find("/Arm"));
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_NE(stage->warnings().front().message.find("a root prim cannot be relocated"), std::string::npos)
        << stage->warnings().front().message;
    EXPECT_EQ(stage->warnings().front().where.line, 5);
}

}  // namespace
}  // namespace obscura::usda
