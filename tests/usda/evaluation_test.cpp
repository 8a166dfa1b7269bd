// Attribute::evaluate: defaults, clamping outside the samples, linear interpolation, held
// values for non-interpolating types, slerp for quaternions, and blocked samples.
#include <cmath>
#include <numbers>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

class EvaluationTest : public ::testing::Test {
protected:
    void SetUp() override {
        stage = test::open(R"(#usda 1.0
def "P"
{
    float f = 7
    float f.timeSamples = {
        0: 0,
        10: 100,
    }
    float onlyDefault = 3
    float nothing
    double3 v.timeSamples = { 0: (0, 0, 0), 4: (4, 8, -4) }
    point3f[] points.timeSamples = { 0: [(0, 0, 0), (1, 1, 1)], 2: [(2, 0, 0), (3, 3, 3)] }
    point3f[] resized.timeSamples = { 0: [(0, 0, 0)], 2: [(2, 0, 0), (3, 3, 3)] }
    matrix4d m.timeSamples = {
        0: ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)),
        1: ((3, 0, 0, 0), (0, 3, 0, 0), (0, 0, 3, 0), (10, 0, 0, 1)),
    }
    int i.timeSamples = { 0: 0, 10: 10 }
    bool b.timeSamples = { 0: false, 10: true }
    token t.timeSamples = { 0: "a", 10: "b" }
    string s.timeSamples = { 0: "x", 10: "y" }
    quatf q.timeSamples = { 0: (1, 0, 0, 0), 1: (0.70710678, 0, 0, 0.70710678) }
    quatd qFlipped.timeSamples = { 0: (1, 0, 0, 0), 1: (-0.70710678, 0, 0, -0.70710678) }
    float blocked.timeSamples = { 0: 1, 5: None, 10: 3 }
}
)");
        ASSERT_TRUE(stage);
        prim = stage->find("/P");
        ASSERT_TRUE(prim);
    }

    Value at(const std::string& attr, double time) {
        const Attribute* attribute = prim->attribute(attr);
        if (!attribute) {
            ADD_FAILURE() << "no attribute " << attr;
            return {};
        }
        const std::optional<Value> value = attribute->evaluate(time);
        if (!value) {
            ADD_FAILURE() << attr << " has no value at " << time;
            return {};
        }
        return *value;
    }

    std::unique_ptr<Stage> stage;
    const Prim* prim = nullptr;
};

TEST_F(EvaluationTest, DefaultWithoutSamples) {
    EXPECT_EQ(at("onlyDefault", 123).numbers, std::vector<double>{3});
    EXPECT_FALSE(prim->attribute("nothing")->evaluate(0));
    EXPECT_FALSE(prim->attribute("onlyDefault")->isAnimated());
}

TEST_F(EvaluationTest, SamplesWinOverDefaultAndClampOutsideTheirRange) {
    EXPECT_EQ(at("f", -5).numbers, std::vector<double>{0});
    EXPECT_EQ(at("f", 0).numbers, std::vector<double>{0});
    EXPECT_EQ(at("f", 10).numbers, std::vector<double>{100});
    EXPECT_EQ(at("f", 50).numbers, std::vector<double>{100});
    EXPECT_TRUE(prim->attribute("f")->isAnimated());
}

TEST_F(EvaluationTest, LinearInterpolation) {
    EXPECT_DOUBLE_EQ(at("f", 2.5).numbers.at(0), 25.0);
    EXPECT_EQ(at("v", 1).numbers, (std::vector<double>{1, 2, -1}));
    EXPECT_EQ(at("points", 1).numbers, (std::vector<double>{1, 0, 0, 2, 2, 2}));
    const Value m = at("m", 0.5);
    EXPECT_DOUBLE_EQ(m.numbers.at(0), 2.0);
    EXPECT_DOUBLE_EQ(m.numbers.at(12), 5.0);
    EXPECT_DOUBLE_EQ(m.numbers.at(15), 1.0);
    EXPECT_EQ(m.typeName, "matrix4d");
}

TEST_F(EvaluationTest, ArraysOfDifferentSizesAreHeld) {
    EXPECT_EQ(at("resized", 1).numbers, (std::vector<double>{0, 0, 0}));
}

TEST_F(EvaluationTest, NonInterpolatingTypesHoldTheEarlierSample) {
    EXPECT_EQ(at("i", 5).numbers, std::vector<double>{0});
    EXPECT_EQ(at("b", 9.99).numbers, std::vector<double>{0});
    EXPECT_EQ(at("b", 10).numbers, std::vector<double>{1});
    EXPECT_EQ(at("t", 9.9).strings, std::vector<std::string>{"a"});
    EXPECT_EQ(at("t", 10).strings, std::vector<std::string>{"b"});
    EXPECT_EQ(at("s", 5).strings, std::vector<std::string>{"x"});
}

TEST_F(EvaluationTest, QuaternionSlerpHalfway) {
    // Halfway between identity and 90 degrees about Z is 45 degrees about Z.
    const double c = std::cos(std::numbers::pi / 8);
    const double s = std::sin(std::numbers::pi / 8);
    const Value q = at("q", 0.5);
    ASSERT_EQ(q.numbers.size(), 4u);
    EXPECT_NEAR(q.numbers[0], c, 1e-6);
    EXPECT_NEAR(q.numbers[1], 0, 1e-9);
    EXPECT_NEAR(q.numbers[2], 0, 1e-9);
    EXPECT_NEAR(q.numbers[3], s, 1e-6);
    // Linear interpolation would not stay unit length: (0.854, 0, 0, 0.354) has length 0.924.
    EXPECT_NEAR(q.numbers[0] * q.numbers[0] + q.numbers[3] * q.numbers[3], 1.0, 1e-9);
}

TEST_F(EvaluationTest, QuaternionSlerpTakesTheShortestPath) {
    // The same rotation written negated must not swing the long way round.
    const Value q = at("qFlipped", 0.5);
    const double sign = q.numbers.at(0) < 0 ? -1.0 : 1.0;
    EXPECT_NEAR(sign * q.numbers[0], std::cos(std::numbers::pi / 8), 1e-6);
    EXPECT_NEAR(sign * q.numbers[3], std::sin(std::numbers::pi / 8), 1e-6);
}

TEST_F(EvaluationTest, BlockedSamples) {
    EXPECT_EQ(at("blocked", 2).numbers, std::vector<double>{1});
    EXPECT_FALSE(prim->attribute("blocked")->evaluate(5));
    EXPECT_FALSE(prim->attribute("blocked")->evaluate(7));
    EXPECT_EQ(at("blocked", 12).numbers, std::vector<double>{3});
}

}  // namespace
}  // namespace obscura::usda
