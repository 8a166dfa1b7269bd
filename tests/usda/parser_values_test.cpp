// Every attribute value type, scalar and array, and the value syntax (numbers, strings, assets,
// tuples, None, dictionaries, untyped metadata values).
#include <cmath>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using test::defaultOf;
using test::open;

struct TypeCase {
    std::string type;
    std::string literal;
    int tupleSize;
    std::vector<double> numbers;
    std::vector<std::string> strings;
};

const std::vector<TypeCase>& typeCases() {
    static const std::vector<TypeCase> cases = {
        {"bool", "true", 1, {1}, {}},
        {"uchar", "255", 1, {255}, {}},
        {"int", "-42", 1, {-42}, {}},
        {"uint", "42", 1, {42}, {}},
        {"int64", "-9007199254740992", 1, {-9007199254740992.0}, {}},
        {"uint64", "18446744073709551615", 1, {18446744073709551615.0}, {}},
        {"half", "0.5", 1, {0.5}, {}},
        {"float", "1.5e3", 1, {1500}, {}},
        {"double", "-2E-2", 1, {-0.02}, {}},
        {"timecode", "24", 1, {24}, {}},
        {"string", R"("a\tb")", 1, {}, {"a\tb"}},
        {"token", "\"tok\"", 1, {}, {"tok"}},
        {"asset", "@textures/wood.png@", 1, {}, {"textures/wood.png"}},
        {"pathExpression", R"("/World/Red*// - /World/Red*/Proxy")", 1, {}, {"/World/Red*// - /World/Red*/Proxy"}},
        {"int2", "(1, 2)", 2, {1, 2}, {}},
        {"int3", "(1, 2, 3)", 3, {1, 2, 3}, {}},
        {"int4", "(1, 2, 3, 4)", 4, {1, 2, 3, 4}, {}},
        {"half2", "(0.5, 1)", 2, {0.5, 1}, {}},
        {"half3", "(0.5, 1, 2)", 3, {0.5, 1, 2}, {}},
        {"half4", "(0.5, 1, 2, 4)", 4, {0.5, 1, 2, 4}, {}},
        {"float2", "(0.5, 1)", 2, {0.5, 1}, {}},
        {"float3", "(0.5, 1, 2)", 3, {0.5, 1, 2}, {}},
        {"float4", "(0.5, 1, 2, 4)", 4, {0.5, 1, 2, 4}, {}},
        {"double2", "(0.5, 1)", 2, {0.5, 1}, {}},
        {"double3", "(0.5, 1, 2)", 3, {0.5, 1, 2}, {}},
        {"double4", "(0.5, 1, 2, 4)", 4, {0.5, 1, 2, 4}, {}},
        {"point3h", "(1, 2, 3)", 3, {1, 2, 3}, {}},
        {"point3f", "(1, 2, 3)", 3, {1, 2, 3}, {}},
        {"point3d", "(1, 2, 3)", 3, {1, 2, 3}, {}},
        {"normal3h", "(0, 0, 1)", 3, {0, 0, 1}, {}},
        {"normal3f", "(0, 0, 1)", 3, {0, 0, 1}, {}},
        {"normal3d", "(0, 0, 1)", 3, {0, 0, 1}, {}},
        {"vector3h", "(1, 0, 0)", 3, {1, 0, 0}, {}},
        {"vector3f", "(1, 0, 0)", 3, {1, 0, 0}, {}},
        {"vector3d", "(1, 0, 0)", 3, {1, 0, 0}, {}},
        {"color3h", "(1, 0.5, 0.25)", 3, {1, 0.5, 0.25}, {}},
        {"color3f", "(1, 0.5, 0.25)", 3, {1, 0.5, 0.25}, {}},
        {"color3d", "(1, 0.5, 0.25)", 3, {1, 0.5, 0.25}, {}},
        {"color4h", "(1, 0.5, 0.25, 1)", 4, {1, 0.5, 0.25, 1}, {}},
        {"color4f", "(1, 0.5, 0.25, 1)", 4, {1, 0.5, 0.25, 1}, {}},
        {"color4d", "(1, 0.5, 0.25, 1)", 4, {1, 0.5, 0.25, 1}, {}},
        {"texCoord2h", "(0.5, 1)", 2, {0.5, 1}, {}},
        {"texCoord2f", "(0.5, 1)", 2, {0.5, 1}, {}},
        {"texCoord2d", "(0.5, 1)", 2, {0.5, 1}, {}},
        {"texCoord3h", "(0.5, 1, 0)", 3, {0.5, 1, 0}, {}},
        {"texCoord3f", "(0.5, 1, 0)", 3, {0.5, 1, 0}, {}},
        {"texCoord3d", "(0.5, 1, 0)", 3, {0.5, 1, 0}, {}},
        {"quath", "(1, 0, 0, 0)", 4, {1, 0, 0, 0}, {}},
        {"quatf", "(0.5, 0.5, 0.5, 0.5)", 4, {0.5, 0.5, 0.5, 0.5}, {}},
        {"quatd", "(0, 1, 0, 0)", 4, {0, 1, 0, 0}, {}},
        {"matrix2d", "((1, 2), (3, 4))", 4, {1, 2, 3, 4}, {}},
        {"matrix3d", "((1, 2, 3), (4, 5, 6), (7, 8, 9))", 9, {1, 2, 3, 4, 5, 6, 7, 8, 9}, {}},
        {"matrix4d",
         "((1, 2, 3, 4), (5, 6, 7, 8), (9, 10, 11, 12), (13, 14, 15, 16))",
         16,
         {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
         {}},
        {"frame4d",
         "( (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (4, 5, 6, 1) )",
         16,
         {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 4, 5, 6, 1},
         {}},
    };
    return cases;
}

template <class T>
std::vector<T> twice(const std::vector<T>& v) {
    std::vector<T> out = v;
    out.insert(out.end(), v.begin(), v.end());
    return out;
}

TEST(ParserValues, EveryTypeAsScalarAndArray) {
    std::string text = "#usda 1.0\ndef \"P\"\n{\n";
    for (size_t i = 0; i < typeCases().size(); ++i) {
        const TypeCase& c = typeCases()[i];
        text += "    " + c.type + " s" + std::to_string(i) + " = " + c.literal + "\n";
        text += "    " + c.type + "[] a" + std::to_string(i) + " = [" + c.literal + ", " + c.literal + "]\n";
    }
    text += "}\n";
    const auto stage = open(text);
    ASSERT_TRUE(stage);
    for (size_t i = 0; i < typeCases().size(); ++i) {
        const TypeCase& c = typeCases()[i];
        SCOPED_TRACE(c.type);
        const Value scalar = defaultOf(*stage, "/P", "s" + std::to_string(i));
        EXPECT_EQ(scalar.typeName, c.type);
        EXPECT_FALSE(scalar.isArray);
        EXPECT_EQ(scalar.tupleSize, c.tupleSize);
        EXPECT_EQ(scalar.numbers, c.numbers);
        EXPECT_EQ(scalar.strings, c.strings);
        EXPECT_EQ(scalar.size(), 1u);

        const Value array = defaultOf(*stage, "/P", "a" + std::to_string(i));
        EXPECT_EQ(array.typeName, c.type);
        EXPECT_TRUE(array.isArray);
        EXPECT_EQ(array.tupleSize, c.tupleSize);
        EXPECT_EQ(array.numbers, twice(c.numbers));
        EXPECT_EQ(array.strings, twice(c.strings));
        EXPECT_EQ(array.size(), 2u);
        EXPECT_EQ(stage->find("/P")->attribute("a" + std::to_string(i))->typeName, c.type + "[]");
    }
}

TEST(ParserValues, SpecialNumbers) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    float posInf = inf
    float negInf = -inf
    double notANumber = nan
    double[] mixed = [1, -2.5, .5, 3., 1e2, -1.25E-1, inf, -inf]
    int negative = -7
    bool yes = 1
    bool no = false
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(defaultOf(*stage, "/P", "posInf").numbers.at(0), INFINITY);
    EXPECT_EQ(defaultOf(*stage, "/P", "negInf").numbers.at(0), -INFINITY);
    EXPECT_TRUE(std::isnan(defaultOf(*stage, "/P", "notANumber").numbers.at(0)));
    EXPECT_EQ(defaultOf(*stage, "/P", "mixed").numbers,
              (std::vector<double>{1, -2.5, 0.5, 3, 100, -0.125, INFINITY, -INFINITY}));
    EXPECT_EQ(defaultOf(*stage, "/P", "negative").numbers, std::vector<double>{-7});
    EXPECT_EQ(defaultOf(*stage, "/P", "yes").numbers, std::vector<double>{1});
    EXPECT_EQ(defaultOf(*stage, "/P", "no").numbers, std::vector<double>{0});
}

TEST(ParserValues, EmptyAndMultiLineArrays) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    float[] empty = []
    point3f[] points = [
        (0, 0, 0),  # first
        (1, 0, 0),  // second
        (0, 1, 0),  /* third, with a
                       trailing comma */
    ]
    matrix4d[] xforms = [
        ( (1, 0, 0, 0),
          (0, 1, 0, 0),
          (0, 0, 1, 0),
          (0, 0, 0, 1) ),
    ]
}
)");
    ASSERT_TRUE(stage);
    const Value empty = defaultOf(*stage, "/P", "empty");
    EXPECT_TRUE(empty.isArray);
    EXPECT_EQ(empty.size(), 0u);
    EXPECT_EQ(empty.typeName, "float");
    const Value points = defaultOf(*stage, "/P", "points");
    EXPECT_EQ(points.size(), 3u);
    EXPECT_EQ(points.numbers, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
    const Value xforms = defaultOf(*stage, "/P", "xforms");
    EXPECT_EQ(xforms.size(), 1u);
    EXPECT_EQ(xforms.numbers.at(15), 1.0);
}

TEST(ParserValues, StringsAndEscapes) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    string doubleQuoted = "say \"hi\"\n\\ \x41\101"
    string singleQuoted = 'it\'s "fine"'
    string empty = ""
    string tripleDouble = """first line
second "quoted" line
third"""
    string tripleSingle = '''a ''b'' c'''
    token[] tokens = ["a", 'b', """c"""]
    string[] lines = ["x", "y"]
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(defaultOf(*stage, "/P", "doubleQuoted").strings.at(0), "say \"hi\"\n\\ AA");
    EXPECT_EQ(defaultOf(*stage, "/P", "singleQuoted").strings.at(0), "it's \"fine\"");
    EXPECT_EQ(defaultOf(*stage, "/P", "empty").strings.at(0), "");
    EXPECT_EQ(defaultOf(*stage, "/P", "tripleDouble").strings.at(0), "first line\nsecond \"quoted\" line\nthird");
    EXPECT_EQ(defaultOf(*stage, "/P", "tripleSingle").strings.at(0), "a ''b'' c");
    EXPECT_EQ(defaultOf(*stage, "/P", "tokens").strings, (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_EQ(defaultOf(*stage, "/P", "lines").strings, (std::vector<std::string>{"x", "y"}));
    // The triple-quoted string spans lines: later locations must still be right.
    EXPECT_EQ(stage->find("/P")->attribute("tripleSingle")->where.line, 10);
}

TEST(ParserValues, AssetPaths) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    asset plain = @./textures/a.png@
    asset tripled = @@@weird@name@@.png@@@
    asset escaped = @@@a\@@@b@@@
    asset[] list = [@a.png@, @@@b.png@@@]
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(defaultOf(*stage, "/P", "plain").strings.at(0), "./textures/a.png");
    EXPECT_EQ(defaultOf(*stage, "/P", "tripled").strings.at(0), "weird@name@@.png");
    EXPECT_EQ(defaultOf(*stage, "/P", "escaped").strings.at(0), "a@@@b");
    EXPECT_EQ(defaultOf(*stage, "/P", "list").strings, (std::vector<std::string>{"a.png", "b.png"}));
}

TEST(ParserValues, NoneBlocksTheDefault) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    float blocked = None
    float declared
}
)");
    ASSERT_TRUE(stage);
    const Prim* prim = stage->find("/P");
    ASSERT_TRUE(prim->attribute("blocked"));
    EXPECT_FALSE(prim->attribute("blocked")->defaultValue);
    ASSERT_TRUE(prim->attribute("declared"));
    EXPECT_FALSE(prim->attribute("declared")->defaultValue);
    EXPECT_EQ(prim->attribute("declared")->typeName, "float");
}

TEST(ParserValues, DictionariesFlattenToKeyPaths) {
    const auto stage = open(R"(#usda 1.0
def "P" (
    customData = {
        string a = "b"; int n = 3
        dictionary inner = {
            double3 v = (1, 2, 3)
            token[] list = ["x", "y"]
        }
        bool "quoted key" = true
    }
)
{
}
)");
    ASSERT_TRUE(stage);
    const auto& metadata = stage->find("/P")->metadata;
    EXPECT_EQ(metadata.at("customData:a").strings, std::vector<std::string>{"b"});
    EXPECT_EQ(metadata.at("customData:n").numbers, std::vector<double>{3});
    EXPECT_EQ(metadata.at("customData:n").typeName, "int");
    EXPECT_EQ(metadata.at("customData:inner:v").numbers, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(metadata.at("customData:inner:v").typeName, "double3");
    EXPECT_EQ(metadata.at("customData:inner:list").strings, (std::vector<std::string>{"x", "y"}));
    EXPECT_TRUE(metadata.at("customData:inner:list").isArray);
    EXPECT_EQ(metadata.at("customData:quoted key").numbers, std::vector<double>{1});
}

TEST(ParserValues, UntypedMetadataGetsTheTypeItLooksLike) {
    const auto stage = open(R"(#usda 1.0
def "P" (
    count = 3
    ratio = 1.5
    triple = (1, 2, 3.5)
    names = ["a", "b"]
    flag = true
    matrix = ((1, 0), (0, 1))
    target = </Other/Prim>
    word = public
    file = @a.usda@
    pairs = [(1, 2), (3, 4)]
)
{
}
)");
    ASSERT_TRUE(stage);
    const auto& m = stage->find("/P")->metadata;
    EXPECT_EQ(m.at("count").typeName, "int");
    EXPECT_EQ(m.at("ratio").typeName, "double");
    EXPECT_EQ(m.at("triple").typeName, "double3");
    EXPECT_EQ(m.at("triple").tupleSize, 3);
    EXPECT_EQ(m.at("names").typeName, "string");
    EXPECT_TRUE(m.at("names").isArray);
    EXPECT_EQ(m.at("flag").typeName, "bool");
    EXPECT_EQ(m.at("matrix").typeName, "matrix2d");
    EXPECT_EQ(m.at("matrix").numbers, (std::vector<double>{1, 0, 0, 1}));
    EXPECT_EQ(m.at("target").typeName, "path");
    EXPECT_EQ(m.at("target").strings, std::vector<std::string>{"/Other/Prim"});
    EXPECT_EQ(m.at("word").typeName, "token");
    EXPECT_EQ(m.at("file").typeName, "asset");
    EXPECT_EQ(m.at("pairs").typeName, "int2");
    EXPECT_EQ(m.at("pairs").size(), 2u);
}

}  // namespace
}  // namespace obscura::usda
