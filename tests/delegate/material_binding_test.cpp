// UsdShade material resolution (harness/material_binding.h) on composed stages: binding purposes
// (Obscura renders "full", falling back to all-purpose bindings, and to a "preview" stand-in where
// the full material is not one it draws), inheritance down namespace and bindMaterialAs,
// collection-based bindings and UsdCollectionAPI membership, GeomSubsets' own bindings; and a
// stage rendered through the scene host with a purpose-restricted binding.
#include "harness/material_binding.h"
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <variant>

namespace obscura::test {
namespace {

std::unique_ptr<usda::Stage> open(const std::string& text) {
    auto opened = usda::Stage::openFromString("#usda 1.0\n" + text, "binding.usda");
    if (auto* error = std::get_if<usda::Error>(&opened)) {
        ADD_FAILURE() << error->message;
        return nullptr;
    }
    return std::move(std::get<std::unique_ptr<usda::Stage>>(opened));
}

// Materials named Prod* stand for renderer-specific surfaces Obscura does not draw.
std::string boundTo(const usda::Stage& stage, const std::string& path, bool ancestors = true) {
    const usda::Prim* prim = stage.find(path);
    if (!prim) return "no prim " + path;
    auto drawable = [](const std::string& material) { return material.find("/Prod") == std::string::npos; };
    return harness::resolveBoundMaterial(stage, *prim, drawable, ancestors).value_or("");
}

TEST(MaterialBinding, FullPurposeIsPreferredToAllPurpose) {
    auto stage = open(R"(
def Mesh "Both"
{
    rel material:binding = </Looks/All>
    rel material:binding:full = </Looks/Full>
}
def Mesh "PreviewAndAll"
{
    rel material:binding:preview = </Looks/Preview>
    rel material:binding = </Looks/All>
}
def Mesh "PreviewOnly"
{
    rel material:binding:preview = </Looks/Preview>
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(boundTo(*stage, "/Both"), "/Looks/Full");
    EXPECT_EQ(boundTo(*stage, "/PreviewAndAll"), "/Looks/All");
    EXPECT_EQ(boundTo(*stage, "/PreviewOnly"), "/Looks/Preview");  // nothing else binds it
}

// A production material Obscura does not draw, bound for every purpose, with a viewport stand-in
// bound for preview: the stand-in is drawn.
TEST(MaterialBinding, PreviewStandInWhereTheFullMaterialIsNotDrawn) {
    auto stage = open(R"(
def Xform "Asset"
{
    rel material:binding = </Looks/ProdSkin>
    rel material:binding:preview = </Looks/Proxy>
    def Mesh "Body"
    {
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(boundTo(*stage, "/Asset/Body"), "/Looks/Proxy");
}

TEST(MaterialBinding, DescendantsWinUnlessTheAncestorIsStronger) {
    auto stage = open(R"(
def Xform "Weak"
{
    rel material:binding = </Looks/Parent>
    def Mesh "Own"
    {
        rel material:binding = </Looks/Child>
    }
    def Mesh "Inherits"
    {
    }
}
def Xform "Strong"
{
    rel material:binding = </Looks/Parent> (
        bindMaterialAs = "strongerThanDescendants"
    )
    def Mesh "Own"
    {
        rel material:binding = </Looks/Child>
    }
}
def Xform "PurposeAbove"
{
    rel material:binding:full = </Looks/Full>
    def Mesh "Own"
    {
        rel material:binding = </Looks/Child>
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(boundTo(*stage, "/Weak/Own"), "/Looks/Child");
    EXPECT_EQ(boundTo(*stage, "/Weak/Inherits"), "/Looks/Parent");
    EXPECT_EQ(boundTo(*stage, "/Strong/Own"), "/Looks/Parent");
    // Rule 3: a full-purpose binding anywhere above beats an all-purpose one on the prim.
    EXPECT_EQ(boundTo(*stage, "/PurposeAbove/Own"), "/Looks/Full");
}

// The UsdShade documentation's chair: metalBits holds the back, less its rivet; the chair's
// collection bindings come before its direct binding, and a direct binding below wins.
TEST(MaterialBinding, CollectionsBindTheirMembersBeneathTheirOwner) {
    auto stage = open(R"(
def Xform "Chair" (
    prepend apiSchemas = ["CollectionAPI:metalBits", "CollectionAPI:legs"]
)
{
    rel collection:metalBits:includes = [</Chair/Back>]
    rel collection:metalBits:excludes = [</Chair/Back/Rivet>]
    rel collection:legs:includes = [</Chair/Legs>, </Elsewhere>]
    uniform token collection:legs:expansionRule = "explicitOnly"
    rel material:binding:collection:metalBits = [</Chair.collection:metalBits>, </Looks/Metal>]
    rel material:binding:collection:legs = [</Looks/Wood>, </Chair.collection:legs>]
    rel material:binding = </Looks/Plastic>
    def Xform "Back"
    {
        def Mesh "Brace"
        {
        }
        def Mesh "Rivet"
        {
        }
        def Mesh "Slat"
        {
            rel material:binding = </Looks/Paint>
        }
    }
    def Mesh "Legs"
    {
        def Mesh "Foot"
        {
        }
    }
    def Mesh "Seat"
    {
    }
}
def Mesh "Elsewhere"
{
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(boundTo(*stage, "/Chair/Back/Brace"), "/Looks/Metal");
    EXPECT_EQ(boundTo(*stage, "/Chair/Back/Rivet"), "/Looks/Plastic");  // excluded: the chair's direct binding
    EXPECT_EQ(boundTo(*stage, "/Chair/Back/Slat"), "/Looks/Paint");
    EXPECT_EQ(boundTo(*stage, "/Chair/Seat"), "/Looks/Plastic");
    EXPECT_EQ(boundTo(*stage, "/Chair/Legs"), "/Looks/Wood");
    EXPECT_EQ(boundTo(*stage, "/Chair/Legs/Foot"), "/Looks/Plastic");  // explicitOnly: not the descendants
    EXPECT_EQ(boundTo(*stage, "/Elsewhere"), "");  // a member, but not beneath the chair
}

TEST(MaterialBinding, CollectionMembership) {
    auto stage = open(R"(
def Xform "Set" (
    prepend apiSchemas = ["CollectionAPI:props", "CollectionAPI:all", "CollectionAPI:everything"]
)
{
    rel collection:props:includes = [</Set/Props>]
    rel collection:props:excludes = [</Set/Props/Lamp>]
    rel collection:all:includes = [</Set.collection:props>, </Set/Walls>]
    rel collection:all:excludes = [</Set/Props/Cup>]
    bool collection:everything:includeRoot = 1
    rel collection:everything:excludes = [</Set/Walls>]
    def Xform "Props"
    {
        def Mesh "Cup"
        {
        }
        def Xform "Lamp"
        {
            def Mesh "Shade"
            {
            }
        }
    }
    def Mesh "Walls"
    {
    }
}
)");
    ASSERT_TRUE(stage);
    auto in = [&](const char* collection, const char* path) { return harness::collectionIncludes(*stage, collection, path); };
    EXPECT_TRUE(in("/Set.collection:props", "/Set/Props/Cup"));
    EXPECT_FALSE(in("/Set.collection:props", "/Set/Props/Lamp/Shade"));  // beneath an exclude
    EXPECT_FALSE(in("/Set.collection:props", "/Set/Walls"));
    EXPECT_TRUE(in("/Set.collection:all", "/Set/Walls"));
    EXPECT_FALSE(in("/Set.collection:all", "/Set/Props/Cup"));  // its own exclude
    EXPECT_FALSE(in("/Set.collection:all", "/Set/Props/Lamp"));  // excluded in the collection it includes
    EXPECT_TRUE(in("/Set.collection:everything", "/Set/Props/Lamp/Shade"));
    EXPECT_FALSE(in("/Set.collection:everything", "/Set/Walls"));
    EXPECT_FALSE(in("/Set.collection:missing", "/Set/Walls"));
    EXPECT_FALSE(in("/Nowhere.collection:props", "/Set/Walls"));
}

// Pattern-based collections (expression mode): the prims the membershipExpression matches, under
// `mode` "expression" or the fallback "automatic" where no include, exclude or includeRoot is
// authored; "relationship" mode, or an include, ignores the expression. A relationship-mode
// collection may include an expression-mode one.
TEST(MaterialBinding, ExpressionCollectionsHoldWhatTheirExpressionMatches) {
    auto stage = open(R"(
def Xform "Set" (
    prepend apiSchemas = ["CollectionAPI:red", "CollectionAPI:spheres", "CollectionAPI:ruled", "CollectionAPI:mixed", "CollectionAPI:both"]
)
{
    uniform pathExpression collection:red:membershipExpression = "Props/Red*//"
    uniform pathExpression collection:spheres:membershipExpression = "//*{isa:Sphere} - %:red"
    uniform token collection:spheres:mode = "expression"
    uniform pathExpression collection:ruled:membershipExpression = "//"
    uniform token collection:ruled:mode = "relationship"
    rel collection:ruled:includes = [</Set/Props/BlueBall>]
    uniform pathExpression collection:mixed:membershipExpression = "//"
    rel collection:mixed:includes = [</Set/Props/BlueBall>]
    rel collection:both:includes = [</Set.collection:red>, </Set/Props/BlueBall>]
    rel material:binding:collection:spheres = [</Set.collection:spheres>, </Looks/Sphere>]
    rel material:binding:collection:red = [</Set.collection:red>, </Looks/Red>]
    def Xform "Props"
    {
        def Mesh "RedCup"
        {
            def Mesh "Handle"
            {
            }
        }
        def Sphere "RedBall"
        {
        }
        def Sphere "BlueBall"
        {
        }
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
    auto in = [&](const char* collection, const char* path) { return harness::collectionIncludes(*stage, collection, path); };
    EXPECT_TRUE(in("/Set.collection:red", "/Set/Props/RedCup/Handle"));
    EXPECT_FALSE(in("/Set.collection:red", "/Set/Props/BlueBall"));
    EXPECT_TRUE(in("/Set.collection:spheres", "/Set/Props/BlueBall"));
    EXPECT_FALSE(in("/Set.collection:spheres", "/Set/Props/RedBall"));  // the referenced collection's
    EXPECT_FALSE(in("/Set.collection:ruled", "/Set/Props/RedCup"));
    EXPECT_TRUE(in("/Set.collection:ruled", "/Set/Props/BlueBall"));
    EXPECT_FALSE(in("/Set.collection:mixed", "/Set/Props/RedCup"));  // automatic: the include decides
    EXPECT_TRUE(in("/Set.collection:both", "/Set/Props/RedCup"));
    // The first collection binding in property order whose collection holds the prim.
    EXPECT_EQ(boundTo(*stage, "/Set/Props/BlueBall"), "/Looks/Sphere");
    EXPECT_EQ(boundTo(*stage, "/Set/Props/RedBall"), "/Looks/Red");
    EXPECT_EQ(boundTo(*stage, "/Set/Props/RedCup/Handle"), "/Looks/Red");
}

// `%_` in a membershipExpression stands for the weaker opinion's expression (SdfPathExpression's
// ComposeOver): a referencing layer adds to the referenced asset's collection; where no weaker
// opinion resolves, it matches nothing.
TEST(MaterialBinding, WeakerExpressionReferencesComposeOver) {
    auto stage = open(R"(
def Xform "Asset" (
    prepend apiSchemas = ["CollectionAPI:set"]
)
{
    uniform pathExpression collection:set:membershipExpression = "Props/Cup"
    def Xform "Props"
    {
        def Mesh "Cup"
        {
        }
        def Mesh "Plate"
        {
        }
        def Mesh "Bowl"
        {
        }
    }
}
def Xform "Shot" (
    references = </Asset>
)
{
    uniform pathExpression collection:set:membershipExpression = "%_ + Props/Plate"
}
)");
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
    auto in = [&](const char* collection, const char* path) { return harness::collectionIncludes(*stage, collection, path); };
    EXPECT_TRUE(in("/Shot.collection:set", "/Shot/Props/Cup"));
    EXPECT_TRUE(in("/Shot.collection:set", "/Shot/Props/Plate"));
    EXPECT_FALSE(in("/Shot.collection:set", "/Shot/Props/Bowl"));
    EXPECT_TRUE(in("/Asset.collection:set", "/Asset/Props/Cup"));
    EXPECT_FALSE(in("/Asset.collection:set", "/Asset/Props/Plate"));
}

// Absolute paths in a referenced asset's expressions (patterns and collection references) are
// mapped through the arc, as relationship targets are: the asset's collections hold the
// referencing prim's descendants.
TEST(MaterialBinding, AbsolutePathsInReferencedExpressionsFollowTheArc) {
    auto stage = open(R"(
def Xform "Asset" (
    prepend apiSchemas = ["CollectionAPI:cups", "CollectionAPI:table"]
)
{
    uniform pathExpression collection:cups:membershipExpression = "/Asset/Props/Cup*"
    uniform pathExpression collection:table:membershipExpression = "/Asset/Props// - %/Asset:cups"
    def Xform "Props"
    {
        def Mesh "CupA"
        {
        }
        def Mesh "Plate"
        {
        }
    }
}
def Xform "Shot" (
    references = </Asset>
)
{
}
)");
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->warnings().empty()) << stage->warnings().front().message;
    auto in = [&](const char* collection, const char* path) { return harness::collectionIncludes(*stage, collection, path); };
    EXPECT_TRUE(in("/Shot.collection:cups", "/Shot/Props/CupA"));
    EXPECT_FALSE(in("/Shot.collection:cups", "/Shot/Props/Plate"));
    EXPECT_TRUE(in("/Shot.collection:table", "/Shot/Props/Plate"));
    EXPECT_FALSE(in("/Shot.collection:table", "/Shot/Props/CupA"));
    EXPECT_TRUE(in("/Asset.collection:cups", "/Asset/Props/CupA"));
}

// Collections that include each other end at a fixed depth, not in a crash.
TEST(MaterialBinding, CollectionsThatIncludeEachOtherEnd) {
    auto stage = open(R"(
def Xform "A" (
    prepend apiSchemas = ["CollectionAPI:a", "CollectionAPI:b"]
)
{
    rel collection:a:includes = [</A.collection:b>]
    rel collection:b:includes = [</A.collection:a>]
    rel material:binding:collection:a = [</A.collection:a>, </Looks/Loop>]
    def Mesh "M"
    {
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_FALSE(harness::collectionIncludes(*stage, "/A.collection:a", "/A/M"));
    EXPECT_EQ(boundTo(*stage, "/A/M"), "");
}

TEST(MaterialBinding, OwnBindingsAloneForSubsets) {
    auto stage = open(R"(
def Mesh "M"
{
    rel material:binding = </Looks/Mesh>
    def GeomSubset "Full"
    {
        rel material:binding:full = </Looks/Full>
    }
    def GeomSubset "None"
    {
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(boundTo(*stage, "/M/Full", false), "/Looks/Full");
    EXPECT_EQ(boundTo(*stage, "/M/None", false), "");
}

// Through the scene host: a mesh bound for the full purpose only (as Houdini writes a box's
// faces) is drawn with that material, not the fallback grey.
TEST(MaterialBinding, TheHostDrawsTheFullPurposeMaterial) {
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + R"(
def Material "Red"
{
    token outputs:surface.connect = </Red/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:diffuseColor = (0.8, 0.1, 0.1)
        token outputs:surface
    }
}
def Mesh "Quad" (
    prepend apiSchemas = ["MaterialBindingAPI"]
)
{
    point3f[] points = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    rel material:binding:full = </Red>
}
)",
                                                  "full.usda"));
    std::vector<float> albedo = scene.renderAlbedo();
    const size_t centre = (size_t(32) * kWidth + 32) * 3;
    EXPECT_NEAR(albedo.at(centre), 0.8f, 0.01f);
    EXPECT_NEAR(albedo.at(centre + 1), 0.1f, 0.01f);
    EXPECT_NEAR(albedo.at(centre + 2), 0.1f, 0.01f);
}

}  // namespace
}  // namespace obscura::test
