// UsdGeomPrimvarsAPI's primvar inheritance on the composed stage: a constant primvar with an
// authored value reaches every descendant that authors no value of its name; one of another
// interpolation, or a blocked one, hands nothing down and stops those above it.
#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

constexpr const char* kTree = R"(#usda 1.0
def Xform "Root"
{
    color3f[] primvars:displayColor = [(1, 0, 0)]
    float primvars:roughness = 0.5
    float[] primvars:weights = [1, 2, 3] (interpolation = "vertex")
    int[] primvars:displayColor:indices = [0]
    def Xform "Middle"
    {
        float primvars:roughness = 0.25 (interpolation = "uniform")
        color3f[] primvars:displayColor
        def Mesh "Leaf"
        {
        }
        def Mesh "Own"
        {
            color3f[] primvars:displayColor = [(0, 0, 1)]
        }
    }
}
)";

TEST(PrimvarInheritance, ConstantPrimvarsReachDescendantsThatAuthorNone) {
    auto stage = test::open(kTree);
    ASSERT_TRUE(stage);
    const Prim& root = *stage->find("/Root");
    const Prim& leaf = *stage->find("/Root/Middle/Leaf");
    const Attribute* inherited = stage->primvar(leaf, "primvars:displayColor");
    ASSERT_TRUE(inherited) << "a declaration without a value does not stop inheritance";
    EXPECT_EQ(inherited, root.attribute("primvars:displayColor"));
    EXPECT_EQ(&stage->primAuthoring(leaf, *inherited), &root);
    EXPECT_EQ(stage->primvar(*stage->find("/Root/Middle/Own"), "primvars:displayColor"),
              stage->find("/Root/Middle/Own")->attribute("primvars:displayColor"))
        << "a prim's own value wins";
    EXPECT_EQ(stage->primvar(leaf, "primvars:roughness"), nullptr) << "a uniform primvar between stops it";
    EXPECT_EQ(stage->primvar(leaf, "primvars:weights"), nullptr) << "a vertex primvar is not inherited";
    const auto handedDown = stage->inheritablePrimvars(*stage->find("/Root/Middle"));
    ASSERT_EQ(handedDown.size(), 1u) << "the :indices companion is no primvar";
    EXPECT_EQ(handedDown.begin()->first, "primvars:displayColor");
}

}  // namespace
}  // namespace obscura::usda
