// Descendants of an instance are instance proxies (OpenUSD's scenegraph instancing): they compose
// only what the instance's own composition arcs bring, so opinions the referencing layers author
// beneath an instance are ignored and every instance of a prototype composes the same descendants.
// The instance's root stays editable; a class its asset inherits reaches every instance; a prim
// that is instanceable without arcs that bring content is no instance.
#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

// Two instances of /Asset and a copy that is not instanceable, each with a local override of
// Geom's colour and a prim of its own beneath; /Untouched is an instance nobody overrides.
constexpr const char* kOverridden = R"(#usda 1.0
class "Asset"
{
    def Mesh "Geom" (inherits = </_class_Geom>)
    {
        color3f[] primvars:displayColor = [(1, 0, 0)]
    }
}
class "_class_Geom"
{
    double size = 2
}
def Xform "First" (instanceable = true
    references = </Asset>)
{
    double3 xformOp:translate = (1, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
    over "Geom"
    {
        color3f[] primvars:displayColor = [(0, 1, 0)]
    }
    def Xform "Extra" {}
}
def Xform "Second" (instanceable = true
    references = </Asset>)
{
    over "Geom" (references = </Other>)
    {
        color3f[] primvars:displayColor = [(0, 0, 1)]
    }
}
def Xform "Untouched" (instanceable = true
    references = </Asset>) {}
def Xform "Copy" (references = </Asset>)
{
    over "Geom"
    {
        color3f[] primvars:displayColor = [(0, 1, 0)]
    }
}
class "Other"
{
    double weight = 3
}
)";

std::vector<double> colourOf(const Stage& stage, const std::string& prim) {
    const Value value = test::defaultOf(stage, prim, "primvars:displayColor");
    return {value.numbers.begin(), value.numbers.end()};
}

TEST(InstanceProxies, OpinionsBeneathAnInstanceAreIgnored) {
    auto stage = test::open(kOverridden);
    ASSERT_TRUE(stage);
    const std::vector<double> red = {1, 0, 0};
    EXPECT_EQ(colourOf(*stage, "/First/Geom"), red) << "the override beneath the first instance";
    EXPECT_EQ(colourOf(*stage, "/Second/Geom"), red) << "the override beneath the second instance";
    EXPECT_EQ(colourOf(*stage, "/Copy/Geom"), std::vector<double>({0, 1, 0})) << "no instance: the override wins";
    EXPECT_EQ(stage->find("/First/Extra"), nullptr) << "a prim the referencing layer adds beneath an instance";
    EXPECT_EQ(stage->find("/Second/Geom")->attribute("weight"), nullptr) << "an arc authored beneath an instance";
    // The instance's root is no proxy: its own opinions stand.
    EXPECT_EQ(test::defaultOf(*stage, "/First", "xformOp:translate").numbers.front(), 1.0);
    // A class the asset inherits is how USD overrides every instance at once.
    EXPECT_EQ(test::defaultOf(*stage, "/Second/Geom", "size").numbers.front(), 2.0);
}

TEST(InstanceProxies, EveryInstanceComposesWhatAnUntouchedOneDoes) {
    auto stage = test::open(kOverridden);
    ASSERT_TRUE(stage);
    const Prim* untouched = stage->find("/Untouched/Geom");
    ASSERT_TRUE(untouched);
    for (const char* path : {"/First/Geom", "/Second/Geom"}) {
        const Prim* prim = stage->find(path);
        ASSERT_TRUE(prim) << path;
        ASSERT_EQ(prim->attributes.size(), untouched->attributes.size()) << path;
        for (const auto& [name, attribute] : untouched->attributes) {
            const Attribute* other = prim->attribute(name);
            ASSERT_TRUE(other && other->defaultValue && attribute.defaultValue) << path << "." << name;
            EXPECT_EQ(other->defaultValue->numbers, attribute.defaultValue->numbers) << path << "." << name;
        }
    }
    const std::string key = stage->find("/Untouched")->instancingKey;
    EXPECT_FALSE(key.empty());
    EXPECT_EQ(stage->find("/First")->instancingKey, key);
    EXPECT_EQ(stage->find("/Second")->instancingKey, key);
}

// Opinions that reach an instance through its ancestors' arcs are the referencing side's too: a
// set's override of the instance's Geom is ignored, as the root layer's is.
TEST(InstanceProxies, OpinionsFromAnAncestorsArcsAreIgnoredBeneathTheInstance) {
    auto stage = test::open(R"(#usda 1.0
class "Asset"
{
    def Mesh "Geom"
    {
        color3f[] primvars:displayColor = [(1, 0, 0)]
    }
}
class "Set"
{
    def Xform "Inst" (instanceable = true
        references = </Asset>)
    {
        over "Geom"
        {
            color3f[] primvars:displayColor = [(0, 1, 0)]
        }
    }
}
def Xform "World" (references = </Set>) {}
def Xform "Alone" (instanceable = true
    references = </Asset>) {}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(colourOf(*stage, "/World/Inst/Geom"), std::vector<double>({1, 0, 0}));
    EXPECT_FALSE(stage->find("/World/Inst")->instancingKey.empty());
    EXPECT_EQ(stage->find("/World/Inst")->instancingKey, stage->find("/Alone")->instancingKey)
        << "the set's arc is not the instance's";
}

// USD ignores instanceable on a prim whose arcs bring nothing: its descendants keep their own
// opinions. A stronger instanceable = false turns an asset's instancing off the same way.
TEST(InstanceProxies, InstanceableWithoutArcsIsNoInstance) {
    auto stage = test::open(R"(#usda 1.0
def Xform "Lone" (instanceable = true)
{
    def Mesh "Geom"
    {
        color3f[] primvars:displayColor = [(0, 1, 0)]
    }
}
class "Asset" (instanceable = true)
{
    def Mesh "Geom"
    {
        color3f[] primvars:displayColor = [(1, 0, 0)]
    }
}
def Xform "Off" (instanceable = false
    references = </Asset>)
{
    over "Geom"
    {
        color3f[] primvars:displayColor = [(0, 1, 0)]
    }
}
def Xform "On" (references = </Asset>)
{
    over "Geom"
    {
        color3f[] primvars:displayColor = [(0, 1, 0)]
    }
}
)");
    ASSERT_TRUE(stage);
    const std::vector<double> green = {0, 1, 0};
    EXPECT_EQ(stage->find("/Lone")->instancingKey, "");
    EXPECT_EQ(colourOf(*stage, "/Lone/Geom"), green);
    EXPECT_EQ(stage->find("/Off")->instancingKey, "");
    EXPECT_EQ(colourOf(*stage, "/Off/Geom"), green);
    EXPECT_NE(stage->find("/On")->instancingKey, "") << "instanceable from the asset";
    EXPECT_EQ(colourOf(*stage, "/On/Geom"), std::vector<double>({1, 0, 0}));
}

// Instances inside a prototype are instances too: their keys hold only their own arcs, so the
// windows of every building, wherever they sit, share one key; what the building's asset says
// beneath a window is an ancestor's opinion there, and ignored.
TEST(InstanceProxies, NestedInstancesShareTheirOwnArcs) {
    auto stage = test::open(R"(#usda 1.0
class "Window"
{
    def Mesh "Pane"
    {
        color3f[] primvars:displayColor = [(0, 0, 1)]
    }
}
class "Building"
{
    def Xform "Left" (instanceable = true
        references = </Window>) {}
    def Xform "Right" (instanceable = true
        references = </Window>)
    {
        over "Pane"
        {
            color3f[] primvars:displayColor = [(1, 1, 0)]
        }
    }
}
def Xform "North" (instanceable = true
    references = </Building>) {}
def Xform "South" (instanceable = true
    references = </Building>) {}
)");
    ASSERT_TRUE(stage);
    const std::string window = stage->find("/North/Left")->instancingKey;
    EXPECT_FALSE(window.empty());
    for (const char* path : {"/North/Right", "/South/Left", "/South/Right"})
        EXPECT_EQ(stage->find(path)->instancingKey, window) << path;
    EXPECT_NE(stage->find("/North")->instancingKey, window);
    EXPECT_EQ(stage->find("/North")->instancingKey, stage->find("/South")->instancingKey);
    EXPECT_EQ(colourOf(*stage, "/South/Right/Pane"), std::vector<double>({0, 0, 1}));
}

}  // namespace
}  // namespace obscura::usda
