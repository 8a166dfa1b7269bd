// Variable expressions (harness/usda/variable_expression.h): their language against
// OpenUSD's "Variable Expressions" guide, and their use in references, sublayers and variant
// selections over the root layer's expressionVariables (tests/usda/data/expressions).
#include "harness/usda/variable_expression.h"

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using test::kDataDir;
using test::openFile;

Value stringValue(const std::string& s) {
    Value v;
    v.typeName = "string";
    v.strings = std::vector<std::string>{s};
    return v;
}

Value numbers(const char* type, std::vector<double> values, bool array) {
    Value v;
    v.typeName = type;
    v.isArray = array;
    v.numbers = std::move(values);
    return v;
}

class VariableExpressionTest : public ::testing::Test {
protected:
    ExpressionVariables variables = {{"SHOT", stringValue("s010")},
                                     {"TAKE", numbers("int", {3}, false)},
                                     {"HERO", numbers("bool", {1}, false)},
                                     {"TAKES", numbers("int", {1, 3, 5}, true)}};

    std::string value(const std::string& text) {
        auto result = evaluateVariableExpression(text, variables);
        if (auto* problem = std::get_if<ExpressionProblem>(&result)) return "problem: " + problem->message;
        return std::get<std::string>(result);
    }
};

TEST_F(VariableExpressionTest, StringsSubstituteVariables) {
    EXPECT_TRUE(isVariableExpression("`\"a\"`"));
    EXPECT_FALSE(isVariableExpression("./a.usda"));
    EXPECT_EQ(value("`\"./shots/${SHOT}/layout.usda\"`"), "./shots/s010/layout.usda");
    EXPECT_EQ(value("`'${SHOT}_${SHOT}'`"), "s010_s010");
    EXPECT_EQ(value("`${SHOT}`"), "s010");
    EXPECT_EQ(value("`\"price: \\${SHOT}\"`"), "price: ${SHOT}");  // an escaped '$' stays literal
    EXPECT_EQ(value("`None`"), "");
}

TEST_F(VariableExpressionTest, FunctionsChooseAndTakeOnlyTheBranchTheyNeed) {
    EXPECT_EQ(value("`if(defined(MISSING), \"${MISSING}\", \"default\")`"), "default");
    EXPECT_EQ(value("`if(defined(SHOT, TAKE), \"${SHOT}\", \"default\")`"), "s010");
    EXPECT_EQ(value("`if(eq(${TAKE}, 3), \"third\", \"other\")`"), "third");
    EXPECT_EQ(value("`if(and(${HERO}, not(lt(${TAKE}, 2))), \"hero\", \"crowd\")`"), "hero");
    EXPECT_EQ(value("`if(or(false, neq(${SHOT}, \"s010\")), \"a\")`"), "");  // no else: None
    EXPECT_EQ(value("`if(contains(${TAKES}, 5), \"has\", \"lacks\")`"), "has");
    EXPECT_EQ(value("`if(contains(${SHOT}, \"01\"), \"has\", \"lacks\")`"), "has");
    EXPECT_EQ(value("`at([\"x\", \"y\", \"z\"], -1)`"), "z");
    EXPECT_EQ(value("`if(eq(len(${TAKES}), 3), at(${SHOT}, 0))`"), "s");
    EXPECT_EQ(value("`if(geq(${TAKE}, 3), if(gt(${TAKE}, 3), \"more\", \"three\"))`"), "three");
}

TEST_F(VariableExpressionTest, BadExpressionsSayWhatIsWrong) {
    EXPECT_EQ(value("`${NOPE}`"), "problem: expression `${NOPE}`: no expression variable 'NOPE'");
    EXPECT_EQ(value("`\"${TAKE}\"`"), "problem: expression `\"${TAKE}\"`: expression variable 'TAKE' is not a string");
    EXPECT_EQ(value("`frob(1)`"), "problem: expression `frob(1)`: unknown function 'frob'");
    EXPECT_EQ(value("`${TAKE}`"), "problem: expression `${TAKE}` is not a string");
    EXPECT_EQ(value("`\"open`"), "problem: expression `\"open`: column 7: unterminated string");
    EXPECT_EQ(value("`if(true)`"), "problem: expression `if(true)`: if() takes 2 or more arguments");
    EXPECT_NE(value("`" + std::string(1000, '[') + "`").find("nested more than 64 deep"), std::string::npos);
}

// The root layer's expressionVariables choose a referenced layer, a sublayer, a variant and
// asset values; an expression that reads an undefined variable only where defined() says it may
// falls back.
TEST(VariableExpressionStage, ArcsSublayersAndVariantSelectionsEvaluate) {
    const auto stage = openFile(kDataDir + "/expressions/root.usda");
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
    EXPECT_EQ(test::defaultOf(*stage, "/Set", "size").numbers.at(0), 2.0);      // shot_b.usda
    EXPECT_NE(stage->find("/Lights"), nullptr);                                   // lighting_b.usda
    EXPECT_EQ(test::defaultOf(*stage, "/Set", "wetness").numbers.at(0), 1.0);   // the "wet" variant
    EXPECT_EQ(test::defaultOf(*stage, "/Fallback", "size").numbers.at(0), 1.0);  // shot_a.usda
    // Asset-valued attributes hold what their expressions evaluate to, defaults and samples alike.
    EXPECT_EQ(test::defaultOf(*stage, "/Texture", "inputs:file").strings.at(0), "./textures/b_albedo.png");
    const Attribute* animated = stage->find("/Texture")->attribute("inputs:animated");
    ASSERT_NE(animated, nullptr);
    EXPECT_EQ(animated->timeSamples.at(1.0).strings.at(0), "./seq_b.0001.png");
}

// An expression that cannot be evaluated is reported where it is written and taken as written.
TEST(VariableExpressionStage, ABadSelectionIsReportedAtItsPrim) {
    const auto stage = test::open(R"(#usda 1.0
def Xform "Set" (
    variants = {
        string look = "`${UNSET}`"
    }
    prepend variantSets = "look"
)
{
    variantSet "look" = {
        "dry" {
        }
    }
}
)");
    ASSERT_TRUE(stage);
    ASSERT_FALSE(stage->warnings().empty());
    EXPECT_NE(stage->warnings()[0].message.find("no expression variable 'UNSET'"), std::string::npos)
        << stage->warnings()[0].message;
    EXPECT_EQ(stage->warnings()[0].where.line, 2);
}

}  // namespace
}  // namespace obscura::usda
