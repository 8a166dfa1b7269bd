// SdfPathExpression (harness/usda/path_expression.h) matched against a composed stage: globs and
// `//`, relative patterns, predicates, the operators' precedence, expression references, and
// parse errors with their column. Cases follow OpenUSD's "Collections and Patterns" guide.
#include "harness/usda/path_expression.h"

#include <algorithm>
#include <set>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

const char* kScene = R"(#usda 1.0
class "_Class"
{
    def Mesh "Inside"
    {
    }
}
def Xform "World" (
    kind = "assembly"
)
{
    def Xform "Clothing" (
        kind = "group"
    )
    {
        def Xform "Shirts" (
            kind = "component"
        )
        {
            def Mesh "RedTee" (
                prepend apiSchemas = ["MaterialBindingAPI"]
            )
            {
                def Mesh "Collar"
                {
                }
            }
            def Sphere "RedBall"
            {
            }
            def Mesh "BlueTee" (
                prepend apiSchemas = ["CollectionAPI:lightLink"]
            )
            {
            }
        }
    }
    def SphereLight "Lamp"
    {
    }
    over "Ghost"
    {
    }
}
)";

class PathExpressionTest : public ::testing::Test {
protected:
    PathExpressionTest() : stage_(test::open(kScene)) {}

    // The paths (of every prim on the stage, class and over prims included; not the pseudo-root) `text` matches,
    // anchored at `anchor`.
    std::set<std::string> matched(const std::string& text, const std::string& anchor = "/",
                                  const PathExpression::Lookup& lookup = nullptr) {
        auto parsed = PathExpression::parse(text, anchor);
        if (auto* problem = std::get_if<std::string>(&parsed)) {
            ADD_FAILURE() << text << ": " << *problem;
            return {};
        }
        auto none = [](const std::string&, const std::string&) { return std::optional<PathExpression>(); };
        std::set<std::string> paths;
        for (const auto& top : stage_->pseudoRoot().children)
            visit(*top, [&](const Prim& prim) {
                if (std::get<PathExpression>(parsed).matches(prim, lookup ? lookup : none)) paths.insert(prim.path);
            });
        return paths;
    }
    std::string problem(const std::string& text) {
        auto parsed = PathExpression::parse(text, "/");
        auto* p = std::get_if<std::string>(&parsed);
        return p ? *p : "parsed";
    }
    static void visit(const Prim& prim, const std::function<void(const Prim&)>& f) {
        f(prim);
        for (const auto& child : prim.children) visit(*child, f);
    }

    std::unique_ptr<Stage> stage_;
};

using Paths = std::set<std::string>;

TEST_F(PathExpressionTest, GlobsMatchOneNameEach) {
    EXPECT_EQ(matched("/World/Clothing/Shirts/Red*"), (Paths{"/World/Clothing/Shirts/RedTee", "/World/Clothing/Shirts/RedBall"}));
    EXPECT_EQ(matched("/World/Clothing/Shirts/?edTee"), (Paths{"/World/Clothing/Shirts/RedTee"}));
    EXPECT_EQ(matched("/World/Clothing/Shirts/[BR]*Tee"),
              (Paths{"/World/Clothing/Shirts/RedTee", "/World/Clothing/Shirts/BlueTee"}));
    EXPECT_EQ(matched("/World/Clothing/Shirts/[!R]*"), (Paths{"/World/Clothing/Shirts/BlueTee"}));
    EXPECT_EQ(matched("/World/Lamp"), (Paths{"/World/Lamp"}));  // a path alone: that prim, not its descendants
    EXPECT_EQ(matched("/World/Clothing/Shirts/RedTee.points"), Paths{});  // a property: no prim
}

TEST_F(PathExpressionTest, DoubleSlashMatchesAnyRunOfDescendants) {
    EXPECT_EQ(matched("/World//Red*"), (Paths{"/World/Clothing/Shirts/RedTee", "/World/Clothing/Shirts/RedBall"}));
    EXPECT_EQ(matched("/World/Clothing/Shirts/Red*//"),
              (Paths{"/World/Clothing/Shirts/RedTee", "/World/Clothing/Shirts/RedTee/Collar", "/World/Clothing/Shirts/RedBall"}));
    EXPECT_EQ(matched("//Collar"), (Paths{"/World/Clothing/Shirts/RedTee/Collar"}));
    EXPECT_EQ(matched("//").size(), 11u);  // every prim
}

TEST_F(PathExpressionTest, RelativePatternsAreAnchoredAtTheCollectionsPrim) {
    EXPECT_EQ(matched("Red*", "/World/Clothing/Shirts"),
              (Paths{"/World/Clothing/Shirts/RedTee", "/World/Clothing/Shirts/RedBall"}));
    EXPECT_EQ(matched("../Lamp", "/World/Clothing"), (Paths{"/World/Lamp"}));
    EXPECT_EQ(matched(".", "/World/Lamp"), (Paths{"/World/Lamp"}));
}

TEST_F(PathExpressionTest, PredicatesQualifyNames) {
    // isa takes subtypes unless strict; class names and type names alike.
    EXPECT_EQ(matched("/World//*{isa:Gprim}"),
              (Paths{"/World/Clothing/Shirts/RedTee", "/World/Clothing/Shirts/RedTee/Collar",
                     "/World/Clothing/Shirts/RedBall", "/World/Clothing/Shirts/BlueTee"}));
    EXPECT_EQ(matched("/World//*{isa(UsdGeomSphere)}"), (Paths{"/World/Clothing/Shirts/RedBall"}));
    EXPECT_EQ(matched("/World//*{isa(Gprim, strict=true)}"), Paths{});
    EXPECT_EQ(matched("{isa:BoundableLightBase}"), (Paths{"/World/Lamp"}));
    // A lone predicate qualifies every prim; `/Prim/{p}` every child.
    EXPECT_EQ(matched("{kind:component}"), (Paths{"/World/Clothing/Shirts"}));
    EXPECT_EQ(matched("{kind:model}"), (Paths{"/World", "/World/Clothing", "/World/Clothing/Shirts"}));
    EXPECT_EQ(matched("{kind(model, strict=true)}"), Paths{});
    EXPECT_EQ(matched("{kind:group}"), (Paths{"/World", "/World/Clothing"}));
    EXPECT_EQ(matched("{model}"), (Paths{"/World", "/World/Clothing", "/World/Clothing/Shirts"}));
    EXPECT_EQ(matched("{group}"), (Paths{"/World", "/World/Clothing"}));
    EXPECT_EQ(matched("/World/{group:false}"), (Paths{"/World/Lamp", "/World/Ghost"}));
    EXPECT_EQ(matched("{hasAPI:MaterialBindingAPI}"), (Paths{"/World/Clothing/Shirts/RedTee"}));
    EXPECT_EQ(matched("{hasAPI(CollectionAPI, instanceName=lightLink)}"), (Paths{"/World/Clothing/Shirts/BlueTee"}));
    EXPECT_EQ(matched("{hasAPI(CollectionAPI, instanceName='shadowLink')}"), Paths{});
    EXPECT_EQ(matched("{abstract}"), (Paths{"/_Class", "/_Class/Inside"}));
    EXPECT_EQ(matched("{specifier:over}"), (Paths{"/World/Ghost"}));
    EXPECT_EQ(matched("/World/{defined:false}"), (Paths{"/World/Ghost"}));
    // not, and, or, parentheses.
    EXPECT_EQ(matched("/World//*{isa:Gprim and not (isa:Sphere or hasAPI:MaterialBindingAPI)}"),
              (Paths{"/World/Clothing/Shirts/RedTee/Collar", "/World/Clothing/Shirts/BlueTee"}));
}

TEST_F(PathExpressionTest, OperatorsBindComplementFirstAndDifferenceLast) {
    const std::string shirts = "/World/Clothing/Shirts/";
    EXPECT_EQ(matched(shirts + "RedTee " + shirts + "BlueTee"), (Paths{shirts + "RedTee", shirts + "BlueTee"}));
    EXPECT_EQ(matched(shirts + "* & " + shirts + "Red*"), (Paths{shirts + "RedTee", shirts + "RedBall"}));
    EXPECT_EQ(matched(shirts + "* - " + shirts + "Red*"), (Paths{shirts + "BlueTee"}));
    // Union binds tighter than intersection: (RedTee + BlueTee) & Blue*.
    EXPECT_EQ(matched(shirts + "RedTee + " + shirts + "BlueTee & " + shirts + "Blue*"), (Paths{shirts + "BlueTee"}));
    // Intersection tighter than difference: * - (Red* & *Ball).
    EXPECT_EQ(matched(shirts + "* - " + shirts + "Red* & " + shirts + "*Ball"), (Paths{shirts + "RedTee", shirts + "BlueTee"}));
    EXPECT_EQ(matched("(" + shirts + "* - " + shirts + "Red*) + /World/Lamp"), (Paths{shirts + "BlueTee", "/World/Lamp"}));
    // "// - /foo" is "~/foo".
    EXPECT_EQ(matched("~/World//").size(), 2u);  // the class and its child
    EXPECT_EQ(matched("// - /World//"), matched("~/World//"));
    EXPECT_EQ(matched(""), Paths{});  // the empty expression matches nothing
}

TEST_F(PathExpressionTest, ReferencesMatchWhatTheReferencedExpressionMatches) {
    auto lookup = [](const std::string& prim, const std::string& name) -> std::optional<PathExpression> {
        if (prim == "/World" && name == "lights") return std::get<PathExpression>(PathExpression::parse("{isa:BoundableLightBase}", prim));
        if (prim == "/World" && name == "loop") return std::get<PathExpression>(PathExpression::parse("%:loop", prim));
        return std::nullopt;
    };
    EXPECT_EQ(matched("%/World:lights + /World/Ghost", "/", lookup), (Paths{"/World/Lamp", "/World/Ghost"}));
    EXPECT_EQ(matched("%:lights", "/World", lookup), (Paths{"/World/Lamp"}));
    EXPECT_EQ(matched("%/World:missing", "/", lookup), Paths{});
    EXPECT_EQ(matched("%:loop", "/World", lookup), Paths{});  // a cycle ends, matching nothing
    EXPECT_EQ(matched("%_ + /World/Lamp", "/World", lookup), (Paths{"/World/Lamp"}));  // no weaker opinion
}

TEST_F(PathExpressionTest, MalformedExpressionsNameTheirColumn) {
    EXPECT_EQ(problem("/World/Lamp)"), "column 12: unexpected ')'");
    EXPECT_EQ(problem("(/World"), "column 8: expected ')'");
    EXPECT_EQ(problem("/World +"), "column 9: expected a pattern");
    EXPECT_EQ(problem("/World/*{isa:Mesh"), "column 9: unclosed '{' or '['");
    EXPECT_EQ(problem("/World/*{frobnicate}"), "column 10: unknown predicate 'frobnicate'");
    EXPECT_EQ(problem("/World/*{variant(look=red)}"), "column 10: the 'variant' predicate is not supported");
    EXPECT_EQ(problem("%/World"), "column 8: expected ':' and a collection name in an expression reference");
    EXPECT_EQ(problem("/World/[ab"), "column 8: unclosed '{' or '['");
}

// No text exhausts the parser's or the matcher's stack: nesting and length are bounded.
TEST_F(PathExpressionTest, DeepOrLongExpressionsAreRefused) {
    EXPECT_EQ(problem(std::string(100000, '(') + "/World"), "column 65: nested more than 64 deep");
    EXPECT_EQ(problem(std::string(100000, '~') + "/World"), "column 65: nested more than 64 deep");
    EXPECT_NE(problem("/World/*{" + std::string(100000, '(') + "model}").find("nested more than 64 deep"), std::string::npos);
    std::string many;
    for (int i = 0; i < 100000; ++i) many += "/World ";
    EXPECT_NE(problem(many).find("more than 4096 terms"), std::string::npos);
    std::string predicates = "/World/*{model";
    for (int i = 0; i < 100000; ++i) predicates += " or model";
    EXPECT_NE(problem(predicates + "}").find("more than 4096 predicate terms"), std::string::npos);
    EXPECT_EQ(matched("/World/" + std::string(5000, '*')), (Paths{"/World/Clothing", "/World/Lamp", "/World/Ghost"}));
}

// A stage whose collection's expression does not parse opens, and says where the expression is.
TEST(PathExpressionStage, AMalformedMembershipExpressionIsReportedWhereItIsWritten) {
    auto stage = test::open(R"(#usda 1.0
def Xform "Set" (
    prepend apiSchemas = ["CollectionAPI:props"]
)
{
    uniform pathExpression collection:props:membershipExpression = "/Set/(Props"
}
)");
    ASSERT_TRUE(stage);
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_EQ(stage->warnings()[0].where.line, 6);
    EXPECT_NE(stage->warnings()[0].message.find("/Set.collection:props:membershipExpression"), std::string::npos)
        << stage->warnings()[0].message;
}

}  // namespace
}  // namespace obscura::usda
