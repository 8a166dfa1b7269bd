// USD's strength order, LIVRPS (local, inherits, variants, relocates, references, payloads,
// specializes), arc by arc, and relocates of the root layer stack: each fixture authors one attribute under several arcs and expects the
// value the composition rules of the USD glossary ("LIVRPS Strength Ordering", "Inherits",
// "Specializes", "VariantSet") give, including the arcs whose opinions travel across references:
// inherits and specializes of a referenced asset are implied in the referencing layer stack, where
// a class's opinions beat the asset's (inherits) or only fill what nothing else says (specializes).
#include <filesystem>
#include <map>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;

using Layers = test::LayerFiles;

double valueOf(const Stage& stage, const std::string& prim, const std::string& attribute = "x") {
    const Prim* p = stage.find(prim);
    const Attribute* a = p ? p->attribute(attribute) : nullptr;
    auto v = a ? a->evaluate(0) : std::nullopt;
    if (!v || v->numbers.empty()) {
        ADD_FAILURE() << "no value for " << prim << "." << attribute;
        return -1;
    }
    return v->numbers[0];
}

// One prim with an opinion on x through each kind of arc; `keep` lists the arcs that stay.
std::string ladder(const std::string& keep) {
    auto has = [&](char arc) { return keep.find(arc) != std::string::npos; };
    std::string metadata;
    if (has('I')) metadata += "    inherits = </Class>\n";
    if (has('V')) metadata += "    variants = { string v = \"on\" }\n    prepend variantSets = \"v\"\n";
    if (has('R')) metadata += "    references = @ref.usda@\n";
    if (has('P')) metadata += "    payload = @payload.usda@\n";
    if (has('S')) metadata += "    specializes = </Base>\n";
    std::string body;
    if (has('L')) body += "    double x = 1\n";
    if (has('V')) body += "    variantSet \"v\" = {\n        \"on\" {\n            double x = 3\n        }\n    }\n";
    return "#usda 1.0\nclass \"Class\"\n{\n    double x = 2\n}\ndef \"Base\"\n{\n    double x = 6\n}\ndef \"Prim\" (\n" +
           metadata + ")\n{\n" + body + "}\n";
}

TEST(Livrps, EachArcIsStrongerThanTheNextKind) {
    const std::map<std::string, std::string> assets = {
        {"ref.usda", "#usda 1.0\n(\n    defaultPrim = \"Asset\"\n)\ndef \"Asset\"\n{\n    double x = 4\n}\n"},
        {"payload.usda", "#usda 1.0\n(\n    defaultPrim = \"Asset\"\n)\ndef \"Asset\"\n{\n    double x = 5\n}\n"}};
    // L 1, I 2, V 3, R 4, P 5, S 6: with the stronger arcs taken away one by one, the next wins.
    const std::vector<std::pair<std::string, double>> cases = {
        {"LIVRPS", 1}, {"IVRPS", 2}, {"VRPS", 3}, {"RPS", 4}, {"PS", 5}, {"S", 6}};
    for (const auto& [keep, expected] : cases) {
        auto files = assets;
        files["root.usda"] = ladder(keep);
        Layers layers(files);
        auto stage = layers.open();
        ASSERT_TRUE(stage) << keep;
        EXPECT_EQ(valueOf(*stage, "/Prim"), expected) << "arcs " << keep;
        EXPECT_TRUE(stage->warnings().empty()) << keep << ": " << stage->warnings().front().message;
    }
}

TEST(Livrps, AClassInTheReferencingLayerOverridesTheAssetItInheritsIn) {
    // The asset's prim inherits </_class_Thing>; the referencing layer's own </_class_Thing> is
    // implied across the reference and beats every opinion of the asset, its class's included.
    Layers layers({{"asset.usda", R"(#usda 1.0
(
    defaultPrim = "Thing"
)
class "_class_Thing"
{
    double x = 10
    double y = 10
}
def "Thing" (
    inherits = </_class_Thing>
)
{
    double y = 11
}
)"},
                   {"root.usda", R"(#usda 1.0
class "_class_Thing"
{
    double x = 20
    double y = 20
}
def "Instance" (
    references = @asset.usda@
)
{
}
def "Plain" (
    references = @asset.usda@
)
{
    double x = 30
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Instance", "x"), 20);
    EXPECT_EQ(valueOf(*stage, "/Instance", "y"), 20);  // stronger than the asset's local opinion
    EXPECT_EQ(valueOf(*stage, "/Plain", "x"), 30);     // local opinions beat every class
}

TEST(Livrps, InheritsReachDescendantsOfTheClass) {
    Layers layers({{"asset.usda", R"(#usda 1.0
(
    defaultPrim = "Thing"
)
class "_class_Thing"
{
    def "Part"
    {
        double x = 1
    }
}
def "Thing" (
    inherits = </_class_Thing>
)
{
}
)"},
                   {"root.usda", R"(#usda 1.0
over "_class_Thing"
{
    over "Part"
    {
        double x = 2
    }
}
def "Instance" (
    references = @asset.usda@
)
{
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Instance/Part"), 2);
}

TEST(Livrps, SpecializesAcrossAReferenceOnlyFillWhatNothingElseSays) {
    // The asset's prim specializes </Base>: the referencing layer's </Base> is implied across the
    // reference and beats the asset's Base, but, unlike a class, not the asset's own opinions.
    Layers layers({{"asset.usda", R"(#usda 1.0
(
    defaultPrim = "Thing"
)
def "Base"
{
    double x = 1
    double y = 1
}
def "Thing" (
    specializes = </Base>
)
{
    double y = 3
}
)"},
                   {"root.usda", R"(#usda 1.0
over "Base"
{
    double x = 5
    double y = 5
}
def "Instance" (
    references = @asset.usda@
    payload = @payload.usda@
)
{
}
)"},
                   {"payload.usda", R"(#usda 1.0
(
    defaultPrim = "P"
)
def "P"
{
    double z = 7
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Instance", "x"), 5);
    EXPECT_EQ(valueOf(*stage, "/Instance", "y"), 3);
    EXPECT_EQ(valueOf(*stage, "/Instance", "z"), 7);
}

TEST(Livrps, SpecializesAreWeakerThanPayloadsOfTheReferencingPrim) {
    // A specializes arc inside a referenced asset is still weaker than the referencing prim's
    // payload: specializes are the weakest arcs of the whole index.
    Layers layers({{"asset.usda", R"(#usda 1.0
(
    defaultPrim = "Thing"
)
def "Base"
{
    double x = 1
}
def "Thing" (
    specializes = </Base>
)
{
}
)"},
                   {"payload.usda", R"(#usda 1.0
(
    defaultPrim = "P"
)
def "P"
{
    double x = 2
}
)"},
                   {"root.usda", R"(#usda 1.0
def "Instance" (
    references = @asset.usda@
    payload = @payload.usda@
)
{
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Instance"), 2);
}

TEST(Livrps, TheReferencingLayersVariantSelectionWins) {
    Layers layers({{"asset.usda", R"(#usda 1.0
(
    defaultPrim = "Thing"
)
def "Thing" (
    variants = { string look = "red" }
    prepend variantSets = "look"
)
{
    variantSet "look" = {
        "blue" {
            double x = 2
        }
        "red" {
            double x = 1
        }
    }
}
)"},
                   {"root.usda", R"(#usda 1.0
def "Instance" (
    references = @asset.usda@
    variants = { string look = "blue" }
)
{
}
def "AsAuthored" (
    references = @asset.usda@
)
{
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Instance"), 2);
    EXPECT_EQ(valueOf(*stage, "/AsAuthored"), 1);
}

TEST(Livrps, NestedVariantsSelectInsideTheirVariant) {
    // The selection of "detail" is authored inside the "lod" variant that holds the set.
    Layers layers(Files{{"root.usda", R"(#usda 1.0
def "Prim" (
    variants = { string lod = "high" }
    prepend variantSets = "lod"
)
{
    variantSet "lod" = {
        "high" (
            variants = { string detail = "fine" }
            prepend variantSets = "detail"
        ) {
            double x = 1
            variantSet "detail" = {
                "coarse" {
                    double y = 2
                }
                "fine" {
                    double y = 3
                }
            }
        }
        "low" {
            double x = 0
        }
    }
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Prim", "x"), 1);
    EXPECT_EQ(valueOf(*stage, "/Prim", "y"), 3);
}

TEST(Livrps, VariantsAreStrongerThanTheReferencesTheyAuthor) {
    // A variant that adds a reference: the variant's own opinion beats the reference's.
    Layers layers({{"asset.usda", "#usda 1.0\n(\n    defaultPrim = \"A\"\n)\ndef \"A\"\n{\n    double x = 4\n    double y = 4\n}\n"},
                   {"root.usda", R"(#usda 1.0
def "Prim" (
    variants = { string v = "on" }
    prepend variantSets = "v"
)
{
    variantSet "v" = {
        "on" (
            references = @asset.usda@
        ) {
            double x = 3
        }
    }
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Prim", "x"), 3);
    EXPECT_EQ(valueOf(*stage, "/Prim", "y"), 4);
}

// Relocates move a prim an asset brings to another place in the referencing namespace: the source
// is gone, the target holds what the source's arcs bring and its own local opinions.
void expectArmRelocated(const Stage& stage) {
    EXPECT_FALSE(stage.find("/Char/Rig/Arm"));
    ASSERT_TRUE(stage.find("/Char/Rig"));
    ASSERT_TRUE(stage.find("/Char/Arm"));
    EXPECT_EQ(valueOf(stage, "/Char/Arm", "x"), 1);  // from the asset's /Char/Rig/Arm
    EXPECT_EQ(valueOf(stage, "/Char/Arm", "z"), 3);  // local, at the target
    EXPECT_EQ(valueOf(stage, "/Char/Arm/Hand", "y"), 2);
    EXPECT_TRUE(stage.warnings().empty()) << stage.warnings().front().message;
}

const char* kRiggedAsset = R"(#usda 1.0
(
    defaultPrim = "Char"
)
def "Char"
{
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
}
)";

TEST(Livrps, RelocatesOnAPrimMoveWhatItsReferenceBrings) {
    Layers layers({{"asset.usda", kRiggedAsset}, {"root.usda", R"(#usda 1.0
def "Char" (
    references = @asset.usda@
    relocates = {
        <Rig/Arm>: <Arm>
    }
)
{
    over "Arm"
    {
        double z = 3
    }
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    expectArmRelocated(*stage);
}

TEST(Livrps, RelocatesInTheLayersMetadata) {
    Layers layers({{"asset.usda", kRiggedAsset}, {"root.usda", R"(#usda 1.0
(
    relocates = {
        </Char/Rig/Arm>: </Char/Arm>
    }
)
def "Char" (
    references = @asset.usda@
)
{
    over "Arm"
    {
        double z = 3
    }
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    expectArmRelocated(*stage);
}

TEST(Livrps, AMissingInheritsTargetWarnsWhereItIsAuthored) {
    Layers layers(Files{{"root.usda", R"(#usda 1.0
def "Prim" (
    inherits = </NoSuchClass>
)
{
    double x = 1
}
)"}});
    auto stage = layers.open();
    ASSERT_TRUE(stage);
    EXPECT_EQ(valueOf(*stage, "/Prim"), 1);
    ASSERT_EQ(stage->warnings().size(), 1u);
    const Warning& warning = stage->warnings().front();
    EXPECT_NE(warning.message.find("</NoSuchClass> not found"), std::string::npos) << warning.message;
    EXPECT_EQ(fs::path(warning.where.file).filename(), "root.usda");
    EXPECT_EQ(warning.where.line, 3);
    EXPECT_GT(warning.where.column, 0);
}

}  // namespace
}  // namespace obscura::usda
