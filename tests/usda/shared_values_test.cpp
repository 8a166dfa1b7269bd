// Composed prims share their layers' values (as OpenUSD's VtArray does): a value copied into a
// prim, or evaluated, holds the layer's elements until someone changes its copy, and the
// composition budget counts such elements once.
#include <string>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

TEST(SharedArray, CopiesShareUntilOneIsEdited) {
    SharedArray<double> a = std::vector<double>{1, 2, 3};
    SharedArray<double> b = a;
    EXPECT_EQ(a.payload(), b.payload());
    b.edit().push_back(4);
    EXPECT_NE(a.payload(), b.payload());
    EXPECT_EQ(a.vector(), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(b.vector(), (std::vector<double>{1, 2, 3, 4}));
    const double* before = b.data();
    b.edit()[0] = 5;  // no other copy: edited in place
    EXPECT_EQ(b.data(), before);
    EXPECT_EQ(b[0], 5);
}

TEST(SharedArray, EmptyArraysHoldNothing) {
    SharedArray<std::string> empty;
    EXPECT_TRUE(empty.empty());
    EXPECT_EQ(empty.payload(), nullptr);
    EXPECT_EQ(empty.begin(), empty.end());
    EXPECT_EQ(empty, SharedArray<std::string>(std::vector<std::string>{}));
}

// A referenced prim's points, composed at three places: the three attributes, and their values at
// a time, hold the one array the layer read.
constexpr const char* kThreeReferences = R"(#usda 1.0
def Xform "A" (references = </Asset>) {}
def Xform "B" (references = </Asset>) {}
def Xform "C" (references = </Asset>) {}
class "Asset"
{
    def Mesh "Geom"
    {
        point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0)]
    }
}
)";

TEST(SharedValues, ComposedPrimsShareTheirLayersValues) {
    auto stage = test::open(kThreeReferences);
    ASSERT_TRUE(stage);
    const void* payload = stage->find("/A/Geom")->attribute("points")->defaultValue->numbers.payload();
    ASSERT_NE(payload, nullptr);
    for (const char* path : {"/B/Geom", "/C/Geom"})
        EXPECT_EQ(stage->find(path)->attribute("points")->defaultValue->numbers.payload(), payload) << path;
    EXPECT_EQ(stage->find("/C/Geom")->attribute("points")->evaluate(0.0)->numbers.payload(), payload);
}

// 400 references to a prim of 100,000 points: 400 copies would be 320 MB, shared they are one.
TEST(SharedValues, TheBudgetCountsSharedValuesOnce) {
    std::string text = "#usda 1.0\n";
    for (int i = 0; i < 400; ++i) text += "def Xform \"P" + std::to_string(i) + "\" (references = </Asset>) {}\n";
    text += "class \"Asset\"\n{\n    def Mesh \"Geom\"\n    {\n        float[] widths = [";
    for (int i = 0; i < 100000; ++i) text += i ? ", 1" : "1";
    text += "]\n    }\n}\n";
    StageOptions options;
    options.limits.maxMemoryBytes = size_t(64) << 20;
    auto stage = test::open(text, "test.usda", options);
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->find("/P399/Geom")->attribute("widths")->defaultValue->numbers.size(), 100000u);
}

// USD's instancing key: instanceable prims with the same arcs (sites and variant selections)
// share it; other arcs or selections, or no arcs, do not.
constexpr const char* kInstances = R"(#usda 1.0
def Xform "Same1" (instanceable = true
    references = </Asset>) {}
def Xform "Same2" (instanceable = true
    references = </Asset>)
{
    double3 xformOp:translate = (1, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def Xform "OtherAsset" (instanceable = true
    references = </Other>) {}
def Xform "Low" (instanceable = true
    references = </Asset>
    variants = { string lod = "low" }) {}
def Xform "NotInstanceable" (references = </Asset>) {}
def Xform "NoArcs" (instanceable = true) {}
class "Asset" (
    variantSets = "lod"
    variants = { string lod = "high" }
)
{
    variantSet "lod" = {
        "high" {
            def Mesh "Geom" {}
        }
        "low" {
            def Mesh "Geom" {}
        }
    }
}
class "Other"
{
    def Mesh "Geom" {}
}
)";

TEST(InstancingKey, SameArcsShareAKey) {
    auto stage = test::open(kInstances);
    ASSERT_TRUE(stage);
    auto key = [&](const char* path) { return stage->find(path)->instancingKey; };
    EXPECT_FALSE(key("/Same1").empty());
    EXPECT_EQ(key("/Same1"), key("/Same2"));
    EXPECT_NE(key("/Same1"), key("/OtherAsset"));
    EXPECT_NE(key("/Same1"), key("/Low"));
    EXPECT_EQ(key("/NotInstanceable"), "");
    EXPECT_EQ(key("/NoArcs"), "");
    EXPECT_EQ(key("/Same1/Geom"), "");  // descendants are not instances themselves
}

}  // namespace
}  // namespace obscura::usda
