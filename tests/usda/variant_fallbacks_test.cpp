// Variant fallbacks (UsdStage's global variant fallbacks): a variant set with no authored
// selection takes the first variant of its fallback list that it has; an authored selection
// always wins; variant sets inside a chosen variant fall back too.
#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

// /Model's "lod" set with three variants, each authoring x; `selection` is authored when not empty.
std::string lodModel(const std::string& selection) {
    const std::string authored =
        selection.empty() ? "" : "    variants = { string lod = \"" + selection + "\" }\n";
    return "#usda 1.0\ndef \"Model\" (\n" + authored + "    prepend variantSets = \"lod\"\n)\n{\n"
           "    variantSet \"lod\" = {\n"
           "        \"high\" {\n            double x = 3\n        }\n"
           "        \"mid\" {\n            double x = 2\n        }\n"
           "        \"low\" {\n            double x = 1\n        }\n"
           "    }\n}\n";
}

StageOptions fallbacks(VariantFallbacks byName) {
    StageOptions options;
    options.variantFallbacks = std::move(byName);
    return options;
}

double xOf(const Stage& stage, const std::string& prim = "/Model") {
    const Value value = test::defaultOf(stage, prim, "x");
    return value.numbers.empty() ? -1 : value.numbers.front();
}

TEST(VariantFallbacks, ASetWithoutSelectionTakesItsFallback) {
    auto stage = test::open(lodModel(""), "model.usda", fallbacks({{"lod", {"low"}}}));
    ASSERT_TRUE(stage);
    EXPECT_EQ(xOf(*stage), 1);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
}

TEST(VariantFallbacks, WithoutFallbacksTheSetIsIgnoredWithAWarning) {
    auto stage = test::open(lodModel(""), "model.usda");
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/Model")->attribute("x"));
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_NE(stage->warnings().front().message.find("has no selection"), std::string::npos);
}

TEST(VariantFallbacks, TheFirstFallbackTheSetHasIsChosen) {
    auto stage = test::open(lodModel(""), "model.usda", fallbacks({{"lod", {"proxy", "mid", "low"}}}));
    ASSERT_TRUE(stage);
    EXPECT_EQ(xOf(*stage), 2);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
}

TEST(VariantFallbacks, FallbacksOfOtherSetsDoNotApply) {
    auto stage = test::open(lodModel(""), "model.usda", fallbacks({{"shading", {"low"}}}));
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/Model")->attribute("x"));
}

TEST(VariantFallbacks, NoneOfTheFallbacksExistingWarns) {
    auto stage = test::open(lodModel(""), "model.usda", fallbacks({{"lod", {"proxy", "draft"}}}));
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/Model")->attribute("x"));
    ASSERT_EQ(stage->warnings().size(), 1u);
    const Warning& warning = stage->warnings().front();
    EXPECT_NE(warning.message.find("none of its fallbacks"), std::string::npos) << warning.message;
    EXPECT_EQ(warning.where.file, "model.usda");
    EXPECT_EQ(warning.where.line, 2);
}

TEST(VariantFallbacks, AnAuthoredSelectionBeatsTheFallback) {
    auto stage = test::open(lodModel("high"), "model.usda", fallbacks({{"lod", {"low"}}}));
    ASSERT_TRUE(stage);
    EXPECT_EQ(xOf(*stage), 3);
}

TEST(VariantFallbacks, AnAuthoredSelectionOfAMissingVariantIsNotReplacedByTheFallback) {
    // Pcp uses fallbacks only where no selection is authored.
    auto stage = test::open(lodModel("ultra"), "model.usda", fallbacks({{"lod", {"low"}}}));
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/Model")->attribute("x"));
    ASSERT_FALSE(stage->warnings().empty());
    EXPECT_NE(stage->warnings().front().message.find("\"ultra\" not found"), std::string::npos);
}

TEST(VariantFallbacks, NestedSetsInsideTheChosenVariantFallBackToo) {
    auto stage = test::open(R"(#usda 1.0
def "Model" (
    prepend variantSets = "lod"
)
{
    variantSet "lod" = {
        "high" (
            prepend variantSets = "detail"
        ) {
            double x = 3
            variantSet "detail" = {
                "fine" {
                    double y = 10
                }
                "coarse" {
                    double y = 20
                }
            }
        }
        "low" {
            double x = 1
        }
    }
}
)",
                            "model.usda", fallbacks({{"lod", {"high"}}, {"detail", {"coarse", "fine"}}}));
    ASSERT_TRUE(stage);
    EXPECT_EQ(xOf(*stage), 3);
    const Value y = test::defaultOf(*stage, "/Model", "y");
    ASSERT_FALSE(y.numbers.empty());
    EXPECT_EQ(y.numbers.front(), 20);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
}

TEST(VariantFallbacks, ApplyToTheSetsOfAReferencedAsset) {
    test::LayerFiles layers({{"model.usda", lodModel("")},
                             {"root.usda", "#usda 1.0\ndef \"Shot\" (\n    references = @model.usda@</Model>\n)\n{\n}\n"}});
    auto stage = layers.open(fallbacks({{"lod", {"mid"}}}));
    ASSERT_TRUE(stage);
    EXPECT_EQ(xOf(*stage, "/Shot"), 2);
}

}  // namespace
}  // namespace obscura::usda
