// Sdf layer offsets: time samples of a layer brought in by a sublayer, reference or payload with
// (offset = o; scale = s) are at o + s t on the stage, through every arc on the way, and a layer
// whose timeCodesPerSecond differs from the layer naming it is rescaled to the namer's.
#include <cmath>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

// A layer whose /Anim animates `x` from 0 at time 0 to 10 at time 10 (x equals the time code).
const char* const kAnimated = R"(#usda 1.0
(
    defaultPrim = "Anim"
)
def "Anim"
{
    double x.timeSamples = {
        0: 0,
        10: 10,
    }
}
)";

double xAt(const Stage& stage, const std::string& path, double time) {
    const Prim* prim = stage.find(path);
    if (!prim || !prim->attribute("x")) {
        ADD_FAILURE() << "no " << path << ".x";
        return NAN;
    }
    const std::optional<Value> value = prim->attribute("x")->evaluate(time);
    return value && !value->numbers.empty() ? value->numbers[0] : NAN;
}

TEST(LayerOffsets, AReferencesOffsetAndScaleMoveItsSamples) {
    test::LayerFiles files({{"anim.usda", kAnimated}, {"root.usda", R"(#usda 1.0
def "Shifted" (references = @anim.usda@ (offset = 5; scale = 2)) {}
def "Plain" (references = @anim.usda@) {}
)"}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    // Layer time t is stage time 5 + 2 t: layer 0 at 5, layer 10 at 25.
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Shifted", 5.0), 0.0);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Shifted", 15.0), 5.0);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Shifted", 25.0), 10.0);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Plain", 5.0), 5.0);
}

TEST(LayerOffsets, OffsetsComposeThroughNestedArcsAndSublayers) {
    // root --sublayer (offset 100)--> shot.usda --payload (offset 10, scale 0.5)--> anim.usda
    test::LayerFiles files({{"anim.usda", kAnimated}, {"shot.usda", R"(#usda 1.0
def "Shot" (payload = @anim.usda@</Anim> (offset = 10; scale = 0.5)) {}
)"},
                            {"root.usda", R"(#usda 1.0
(
    subLayers = [@shot.usda@ (offset = 100)]
)
)"}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    // Layer time t: 10 + 0.5 t in shot.usda, then 100 more on the stage.
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Shot", 110.0), 0.0);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Shot", 112.5), 5.0);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Shot", 115.0), 10.0);
}

TEST(LayerOffsets, ALayerAtOtherTimeCodesPerSecondIsRescaled) {
    // anim48.usda counts 48 codes a second; the stage 24: its time 10 is the stage's 5.
    std::string anim48 = kAnimated;
    anim48.replace(anim48.find("defaultPrim"), 0, "timeCodesPerSecond = 48\n    ");
    test::LayerFiles files({{"anim48.usda", anim48}, {"root.usda", R"(#usda 1.0
(
    timeCodesPerSecond = 24
)
def "Fast" (references = @anim48.usda@) {}
def "FastShifted" (references = @anim48.usda@ (offset = 1)) {}
)"}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Fast", 5.0), 10.0);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/Fast", 2.5), 5.0);
    // The offset is in the referencing layer's codes, after the rescale.
    EXPECT_DOUBLE_EQ(xAt(*stage, "/FastShifted", 6.0), 10.0);
}

TEST(LayerOffsets, ADefaultValueIsTimeless) {
    test::LayerFiles files({{"still.usda", R"(#usda 1.0
def "Still"
{
    double x = 3
}
)"},
                            {"root.usda", R"(#usda 1.0
def "S" (references = @still.usda@</Still> (offset = 50; scale = 3)) {}
)"}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/S", 0.0), 3.0);
    EXPECT_DOUBLE_EQ(xAt(*stage, "/S", 1000.0), 3.0);
}

TEST(LayerOffsets, AZeroScaleIsReportedAtItsPlaceAndIgnored) {
    test::LayerFiles files({{"anim.usda", kAnimated}, {"root.usda", R"(#usda 1.0
def "S" (references = @anim.usda@ (offset = 5; scale = 0)) {}
)"}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_EQ(stage->warnings()[0].where.line, 2);
    EXPECT_NE(stage->warnings()[0].message.find("scale"), std::string::npos) << stage->warnings()[0].message;
    // The scale is dropped, the valid offset kept.
    EXPECT_DOUBLE_EQ(xAt(*stage, "/S", 10.0), 5.0);
}

}  // namespace
}  // namespace obscura::usda
