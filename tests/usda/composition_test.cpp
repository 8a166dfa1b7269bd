// Stage composition: sublayers, overs, references, payloads, inherits, variants, list editing,
// path remapping, and the errors composition can raise.
#include <algorithm>
#include <optional>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using test::defaultOf;
using test::kDataDir;
using test::open;
using test::openError;
using test::openFile;

std::vector<std::string> paths(const std::vector<const Prim*>& prims) {
    std::vector<std::string> out;
    for (const Prim* prim : prims) out.push_back(prim->path);
    return out;
}

std::vector<std::string> childNames(const Prim& prim) {
    std::vector<std::string> out;
    for (const auto& child : prim.children) out.push_back(child->name);
    return out;
}

TEST(Composition, SublayersStrongerFirst) {
    const auto stage = openFile(kDataDir + "/sublayers/root.usda");
    ASSERT_TRUE(stage);
    // root > strong > strong's own sublayer nested/deep > weak
    EXPECT_EQ(defaultOf(*stage, "/World/Ball", "radius").numbers.at(0), 3.0);
    EXPECT_EQ(defaultOf(*stage, "/World/Ball", "primvars:displayColor").numbers, (std::vector<double>{1, 0, 0}));
    EXPECT_EQ(defaultOf(*stage, "/World/Ball", "opacity").numbers.at(0), 0.25);
    EXPECT_EQ(defaultOf(*stage, "/World/Ball", "purpose").strings.at(0), "render");
    const Prim* world = stage->find("/World");
    ASSERT_TRUE(world);
    EXPECT_EQ(world->specifier, Specifier::Def);
    EXPECT_EQ(world->typeName, "Xform");
    EXPECT_EQ(stage->find("/World/Ball")->typeName, "Sphere");
    EXPECT_EQ(paths(stage->prims()), (std::vector<std::string>{"/World", "/World/Ball", "/World/Extra"}));
    // Stage metadata comes from the root layer only.
    EXPECT_EQ(stage->metadata().upAxis, "Y");
    EXPECT_EQ(stage->metadata().metersPerUnit, 0.01);
    EXPECT_EQ(stage->metadata().defaultPrim, "World");
}

TEST(Composition, OverAloneDefinesNothing) {
    const auto stage = open(R"(#usda 1.0
def Xform "World"
{
}

over "Ghost"
{
    def Cube "UnderGhost"
    {
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->find("/Ghost")->specifier, Specifier::Over);
    EXPECT_EQ(stage->find("/Ghost/UnderGhost")->specifier, Specifier::Def);
    // An undefined prim prunes its subtree from traversal, as in USD.
    EXPECT_EQ(paths(stage->prims()), std::vector<std::string>{"/World"});
}

const std::string kReferencingScene = R"(#usda 1.0
def Xform "World"
{
    def "Chair" (
        references = @asset.usda@
    )
    {
        over "Geom"
        {
            float size = 5
        }
    }

    def "Box" (
        prepend references = @./asset.usda@</Other>
    )
    {
    }

    def "Copy" (
        references = </World/Chair>
    )
    {
    }

    def "Heavy" (
        payload = @payload.usda@
    )
    {
    }

    def "Both" (
        references = [@asset.usda@</Other>, @asset.usda@]
    )
    {
    }

    def "NoDefault" (
        references = @nodefault.usda@
    )
    {
    }
}
)";

class ReferenceTest : public ::testing::Test {
protected:
    void SetUp() override {
        stage = open(kReferencingScene, kDataDir + "/refs/scene.usda");
        ASSERT_TRUE(stage);
    }
    std::unique_ptr<Stage> stage;
};

TEST_F(ReferenceTest, DefaultPrimIsGraftedWithLocalOpinionsStronger) {
    const Prim* chair = stage->find("/World/Chair");
    ASSERT_TRUE(chair);
    EXPECT_EQ(chair->typeName, "Xform");
    EXPECT_EQ(chair->kind, "component");
    EXPECT_EQ(childNames(*chair), (std::vector<std::string>{"Geom", "Looks"}));
    EXPECT_EQ(defaultOf(*stage, "/World/Chair/Geom", "size").numbers.at(0), 5.0);
    EXPECT_EQ(defaultOf(*stage, "/World/Chair/Geom", "points").size(), 3u);
    EXPECT_EQ(stage->find("/World/Chair/Geom")->typeName, "Mesh");
    EXPECT_EQ(stage->find("/World/Chair/Geom")->specifier, Specifier::Def);
}

TEST_F(ReferenceTest, TargetsAndConnectionsInsideTheReferenceAreRemapped) {
    const Relationship* binding = stage->find("/World/Chair/Geom")->relationship("material:binding");
    ASSERT_TRUE(binding);
    EXPECT_EQ(binding->targets, std::vector<std::string>{"/World/Chair/Looks/Red"});
    const Attribute* surface = stage->find("/World/Chair/Looks/Red")->attribute("outputs:surface");
    ASSERT_TRUE(surface);
    EXPECT_EQ(surface->connection, "/World/Chair/Looks/Red/Shader.outputs:surface");
}

TEST_F(ReferenceTest, ExplicitPrimPath) {
    EXPECT_EQ(stage->find("/World/Box")->typeName, "Xform");
    EXPECT_EQ(stage->find("/World/Box/Box")->typeName, "Cube");
    EXPECT_EQ(defaultOf(*stage, "/World/Box", "label").strings.at(0), "other");
}

TEST_F(ReferenceTest, InternalReferenceComposesTheTargetAndRemapsThroughBothArcs) {
    EXPECT_EQ(stage->find("/World/Copy")->typeName, "Xform");
    EXPECT_EQ(defaultOf(*stage, "/World/Copy/Geom", "size").numbers.at(0), 5.0);
    EXPECT_EQ(stage->find("/World/Copy/Geom")->relationship("material:binding")->targets,
              std::vector<std::string>{"/World/Copy/Looks/Red"});
}

TEST_F(ReferenceTest, Payload) {
    EXPECT_EQ(stage->find("/World/Heavy")->typeName, "Xform");
    EXPECT_EQ(defaultOf(*stage, "/World/Heavy/Body", "faceVertexCounts").numbers, std::vector<double>{4});
}

TEST_F(ReferenceTest, SeveralReferencesEarlierIsStronger) {
    const Prim* both = stage->find("/World/Both");
    ASSERT_TRUE(both);
    EXPECT_EQ(defaultOf(*stage, "/World/Both", "label").strings.at(0), "other");
    // Children come weakest first: the second reference's, then the first's.
    EXPECT_EQ(childNames(*both), (std::vector<std::string>{"Geom", "Looks", "Box"}));
}

TEST_F(ReferenceTest, MissingDefaultPrimFallsBackToTheFirstRootPrimWithAWarning) {
    EXPECT_EQ(stage->find("/World/NoDefault/Inside")->typeName, "Cube");
    bool warned = false;
    for (const Warning& warning : stage->warnings())
        warned = warned || warning.message.find("has no defaultPrim") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST_F(ReferenceTest, PrimsAreDepthFirstParentsFirst) {
    const std::vector<std::string> all = paths(stage->prims());
    ASSERT_FALSE(all.empty());
    EXPECT_EQ(all.front(), "/World");
    for (size_t i = 0; i < all.size(); ++i) {
        const Prim* prim = stage->find(all[i]);
        ASSERT_TRUE(prim);
        if (prim->parent && prim->parent != &stage->pseudoRoot()) {
            const auto parentAt = std::find(all.begin(), all.end(), prim->parent->path);
            EXPECT_LT(parentAt - all.begin(), static_cast<std::ptrdiff_t>(i));
        }
    }
    const auto chair = std::find(all.begin(), all.end(), "/World/Chair");
    ASSERT_NE(chair, all.end());
    EXPECT_EQ(*(chair + 1), "/World/Chair/Geom");
    EXPECT_EQ(*(chair + 2), "/World/Chair/Looks");
}

TEST(Composition, ArcOnAChildIsStrongerThanTheSameKindOfArcFromItsParent) {
    // Geom gets opinions from the Chair's reference (ancestral) and from its own reference;
    // as in Pcp, the arc authored deeper in namespace wins.
    const auto stage = open(R"(#usda 1.0
def "Chair" (
    references = @asset.usda@
)
{
    over "Geom" (
        references = @geom_override.usda@
    )
    {
    }
}
)",
                            kDataDir + "/refs/depth.usda");
    ASSERT_TRUE(stage);
    EXPECT_EQ(defaultOf(*stage, "/Chair/Geom", "size").numbers.at(0), 2.0);
    EXPECT_EQ(defaultOf(*stage, "/Chair/Geom", "points").size(), 3u);
}

TEST(Composition, ListEditedReferencesAcrossSublayers) {
    // The weaker sublayer references First and Second; this layer deletes First and prepends Other.
    const auto stage = open(R"(#usda 1.0
(
    subLayers = [@listop_weak.usda@]
)

over "Target" (
    delete references = @nodefault.usda@</First>
    prepend references = @asset.usda@</Other>
)
{
}
)",
                            kDataDir + "/refs/edited.usda");
    ASSERT_TRUE(stage);
    EXPECT_EQ(childNames(*stage->find("/Target")), std::vector<std::string>{"Box"});
    EXPECT_EQ(stage->find("/Target")->typeName, "Xform");
    EXPECT_EQ(defaultOf(*stage, "/Target", "label").strings.at(0), "other");
}

TEST(Composition, ApiSchemasComposeAsListOps) {
    const auto stage = open(R"(#usda 1.0
def "A" (
    apiSchemas = ["One", "Two"]
)
{
}
def "B" (
    inherits = </A>
    prepend apiSchemas = ["Zero"]
    delete apiSchemas = ["Two"]
)
{
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->find("/B")->apiSchemas, (std::vector<std::string>{"Zero", "One"}));
}

TEST(Composition, InheritsFromClassIsWeakerThanLocal) {
    const auto stage = open(R"(#usda 1.0
class "_class_Tree"
{
    float height = 10
    float width = 2
    rel self = </_class_Tree/Leaves>

    def Cone "Leaves"
    {
    }
}

def Xform "Forest"
{
    def "Tree1" (
        inherits = </_class_Tree>
    )
    {
        float height = 20
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(defaultOf(*stage, "/Forest/Tree1", "height").numbers.at(0), 20.0);
    EXPECT_EQ(defaultOf(*stage, "/Forest/Tree1", "width").numbers.at(0), 2.0);
    EXPECT_EQ(stage->find("/Forest/Tree1")->specifier, Specifier::Def);
    EXPECT_EQ(stage->find("/Forest/Tree1/Leaves")->typeName, "Cone");
    EXPECT_EQ(stage->find("/Forest/Tree1")->relationship("self")->targets,
              std::vector<std::string>{"/Forest/Tree1/Leaves"});
    EXPECT_EQ(stage->find("/_class_Tree")->specifier, Specifier::Class);
    EXPECT_EQ(paths(stage->prims()), (std::vector<std::string>{"/Forest", "/Forest/Tree1", "/Forest/Tree1/Leaves"}));
}

TEST(Composition, InactivePrimsAndTheirSubtreesAreNotListed) {
    const auto stage = open(R"(#usda 1.0
def "On"
{
    def "Off" (
        active = false
    )
    {
        def "Kid"
        {
        }
    }
    def "Sibling"
    {
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/On/Off")->active);
    EXPECT_TRUE(stage->find("/On/Off/Kid"));
    EXPECT_EQ(paths(stage->prims()), (std::vector<std::string>{"/On", "/On/Sibling"}));
}

TEST(Composition, StrongerLayerCanDeactivateAndBlock) {
    const auto stage = open(R"(#usda 1.0
(
    subLayers = [@weak.usda@]
)
over "World"
{
    over "Ball" (
        active = false
    )
    {
    }
}
)",
                            kDataDir + "/sublayers/blocker.usda");
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/World/Ball")->active);
    EXPECT_EQ(paths(stage->prims()), std::vector<std::string>{"/World"});

    const auto blocked = open(R"(#usda 1.0
(
    subLayers = [@weak.usda@]
)
over "World"
{
    over "Ball"
    {
        double radius = None
    }
}
)",
                              kDataDir + "/sublayers/blocker.usda");
    ASSERT_TRUE(blocked);
    ASSERT_TRUE(blocked->find("/World/Ball")->attribute("radius"));
    EXPECT_FALSE(blocked->find("/World/Ball")->attribute("radius")->defaultValue);
}

// Value resolution takes the strongest opinion that has a value, its time samples before its
// default: a stronger default hides weaker time samples, None hides everything weaker, and
// AnimationBlock (OpenUSD 25.05) hides only the weaker time samples, so the weaker default shows.
TEST(Composition, StrongestOpinionWithAValueWinsAndAnimationBlockHidesOnlyWeakerSamples) {
    const auto stage = open(R"(#usda 1.0
def Xform "Weak"
{
    double blockedAnimation = 1
    double blockedAnimation.timeSamples = { 0: 10, 10: 20 }
    double strongerDefault = 2
    double strongerDefault.timeSamples = { 0: 10, 10: 20 }
    double blocked = 3
    double blocked.timeSamples = { 0: 10, 10: 20 }
    double samplesOnly.timeSamples = { 0: 10, 10: 20 }
    double strongerSamples = AnimationBlock
}
def Xform "Strong" (
    references = </Weak>
)
{
    double blockedAnimation = AnimationBlock
    double strongerDefault = 5
    double blocked = None
    double samplesOnly = AnimationBlock
    double samplesOnly.timeSamples = { 0: 7, 10: 9 }
    double strongerSamples.timeSamples = { 0: 4 }
}
)");
    ASSERT_TRUE(stage);
    const Prim& prim = *stage->find("/Strong");
    auto at = [&](const char* name, double time) -> std::optional<double> {
        const Attribute* attr = prim.attribute(name);
        if (!attr) return std::nullopt;
        std::optional<Value> value = attr->evaluate(time);
        if (!value || value->blocked || value->numbers.empty()) return std::nullopt;
        return value->numbers[0];
    };
    EXPECT_EQ(at("blockedAnimation", 5.0), 1.0);
    EXPECT_EQ(at("strongerDefault", 5.0), 5.0);
    EXPECT_EQ(at("blocked", 5.0), std::nullopt);
    // In one opinion its time samples win over its AnimationBlock.
    EXPECT_EQ(at("samplesOnly", 5.0), 8.0);
    EXPECT_EQ(at("strongerSamples", 5.0), 4.0);
    // And the weaker layer's own samples still animate where no stronger opinion speaks.
    const Prim& weak = *stage->find("/Weak");
    EXPECT_EQ(weak.attribute("blockedAnimation")->evaluate(5.0)->numbers.at(0), 15.0);
}

TEST(Composition, VariantSelectionComposesTheSelectedVariant) {
    const auto stage = open(R"(#usda 1.0
def "Local" (
    variants = { string shape = "sphere" }
)
{
    variantSet "shape" = {
        "cube" {
            def Cube "Geom"
            {
            }
        }
        "sphere" {
            def Sphere "Geom"
            {
                double radius = 4
            }
            float fromVariant = 1
        }
    }
    float fromVariant = 2
}

def "FromAsset" (
    references = @variants.usda@
)
{
}

def "Overridden" (
    references = @variants.usda@
    variants = { string shape = "sphere" }
)
{
}
)",
                            kDataDir + "/refs/variant_scene.usda");
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->find("/Local/Geom")->typeName, "Sphere");
    EXPECT_EQ(defaultOf(*stage, "/Local/Geom", "radius").numbers.at(0), 4.0);
    // Local opinions are stronger than the variant's.
    EXPECT_EQ(defaultOf(*stage, "/Local", "fromVariant").numbers.at(0), 2.0);
    EXPECT_EQ(stage->find("/FromAsset/Geom")->typeName, "Cube");
    // A selection on the referencing prim beats the asset's own.
    EXPECT_EQ(stage->find("/Overridden/Geom")->typeName, "Sphere");
    EXPECT_EQ(stage->find("/Overridden")->kind, "component");
}

TEST(Composition, VariantSetWithoutSelectionIsSkippedWithAWarning) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    variantSet "shape" = {
        "cube" {
            def Cube "Geom"
            {
            }
        }
    }
}
)");
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/P/Geom"));
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_NE(stage->warnings()[0].message.find("no selection"), std::string::npos);
}

TEST(Composition, ReferenceCycleAcrossFilesIsAnError) {
    auto result = Stage::open(kDataDir + "/cycle/a.usda");
    ASSERT_TRUE(std::holds_alternative<Error>(result));
    const Error& error = std::get<Error>(result);
    EXPECT_NE(error.message.find("cycle"), std::string::npos) << error.str();
    EXPECT_EQ(error.where.file, kDataDir + "/cycle/b.usda");
    EXPECT_EQ(error.where.line, 7);
    EXPECT_EQ(error.where.column, 18);
}

TEST(Composition, InternalReferenceToAnAncestorIsACycle) {
    const Error error = openError(R"(#usda 1.0
def "A"
{
    def "B" (
        references = </A>
    )
    {
    }
}
)");
    EXPECT_NE(error.message.find("cycle"), std::string::npos) << error.str();
    EXPECT_EQ(error.where.line, 5);
    EXPECT_EQ(error.where.column, 22);
}

TEST(Composition, SublayerCycleIsAnError) {
    auto result = Stage::open(kDataDir + "/cycle/sub_a.usda");
    ASSERT_TRUE(std::holds_alternative<Error>(result));
    EXPECT_NE(std::get<Error>(result).message.find("sublayer cycle"), std::string::npos);
}

TEST(Composition, UnresolvedInternalReferenceWarns) {
    const auto stage = open(R"(#usda 1.0
def "A" (
    references = </Nowhere>
)
{
}
)");
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->find("/A"));
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_EQ(stage->warnings()[0].where.line, 3);
}

}  // namespace
}  // namespace obscura::usda
