// Layer structure: layer and prim metadata, list ops, properties, time samples, connections,
// relationships, comments and variant sets.
#include "harness/usda/usda_parser.h"
#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using test::defaultOf;
using test::open;

std::unique_ptr<Layer> parse(const std::string& text) {
    auto result = parseLayer(text, "layer.usda");
    if (const Error* error = std::get_if<Error>(&result)) {
        ADD_FAILURE() << error->str();
        return nullptr;
    }
    return std::move(std::get<std::unique_ptr<Layer>>(result));
}

TEST(ParserSyntax, LayerMetadata) {
    const auto stage = open(R"(#usda 1.0
(
    "a comment string"
    doc = """Layer
documentation"""
    upAxis = "Z"
    metersPerUnit = 1
    timeCodesPerSecond = 30
    framesPerSecond = 60
    startTimeCode = 1
    endTimeCode = 240.5
    defaultPrim = "World"
    customLayerData = {
        string creator = "test"
    }
    unknownThing = [1, 2, 3]
    relocates = {
        </A>: </B>
    }
)

def "World"
{
}
)");
    ASSERT_TRUE(stage);
    const StageMetadata& m = stage->metadata();
    EXPECT_EQ(m.upAxis, "Z");
    EXPECT_EQ(m.metersPerUnit, 1.0);
    EXPECT_EQ(m.timeCodesPerSecond, 30.0);
    EXPECT_EQ(m.framesPerSecond, 60.0);
    EXPECT_EQ(m.startTimeCode, 1.0);
    EXPECT_EQ(m.endTimeCode, 240.5);
    EXPECT_EQ(m.defaultPrim, "World");
    EXPECT_EQ(m.doc, "Layer\ndocumentation");
}

TEST(ParserSyntax, StageMetadataDefaults) {
    const auto stage = open("#usda 1.0\n");
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->metadata().upAxis, "Y");
    EXPECT_EQ(stage->metadata().metersPerUnit, 0.01);
    EXPECT_EQ(stage->metadata().timeCodesPerSecond, 24.0);
    EXPECT_FALSE(stage->metadata().startTimeCode);
    EXPECT_TRUE(stage->prims().empty());
    EXPECT_EQ(stage->pseudoRoot().path, "/");
    EXPECT_EQ(stage->find("/"), &stage->pseudoRoot());
}

TEST(ParserSyntax, PrimSpecifiersTypesAndMetadata) {
    const auto layer = parse(R"(#usda 1.0
def Xform "A" (
    kind = "component"
    active = false
    instanceable = true
    hidden = true
    "prim comment"
    doc = "documented"
    apiSchemas = ["MaterialBindingAPI", "SkelBindingAPI"]
)
{
}
over "B"
{
}
class Scope "C" ( kind = "group"; active = true )
{
}
def Some.Qualified "D"
{
}
)");
    ASSERT_TRUE(layer);
    const PrimSpec* a = layer->pseudoRoot.child("A");
    ASSERT_TRUE(a);
    EXPECT_EQ(a->specifier, Specifier::Def);
    EXPECT_EQ(a->typeName, "Xform");
    EXPECT_EQ(a->metadata.at("kind").strings.at(0), "component");
    EXPECT_EQ(a->metadata.at("kind").typeName, "token");
    EXPECT_EQ(a->metadata.at("active").numbers.at(0), 0.0);
    EXPECT_EQ(a->metadata.at("instanceable").numbers.at(0), 1.0);
    EXPECT_EQ(a->metadata.at("hidden").typeName, "bool");
    EXPECT_EQ(a->metadata.at("comment").strings.at(0), "prim comment");
    EXPECT_EQ(a->metadata.at("documentation").strings.at(0), "documented");
    ASSERT_TRUE(a->apiSchemas.explicitItems);
    EXPECT_EQ(*a->apiSchemas.explicitItems, (std::vector<std::string>{"MaterialBindingAPI", "SkelBindingAPI"}));
    EXPECT_EQ(layer->pseudoRoot.child("B")->specifier, Specifier::Over);
    EXPECT_EQ(layer->pseudoRoot.child("C")->specifier, Specifier::Class);
    EXPECT_EQ(layer->pseudoRoot.child("C")->metadata.at("kind").strings.at(0), "group");
    EXPECT_EQ(layer->pseudoRoot.child("D")->typeName, "Some.Qualified");
    EXPECT_EQ(a->where.line, 2);
    EXPECT_EQ(a->where.column, 1);
    EXPECT_EQ(a->where.file, "layer.usda");
}

TEST(ParserSyntax, ListOpPrefixes) {
    const auto layer = parse(R"(#usda 1.0
def "P" (
    prepend references = @a.usda@</A>
    append references = [@b.usda@, </Internal>]
    delete references = @c.usda@
    add payload = @p.usda@</P> (offset = 0; scale = 1)
    reorder inherits = [</C2>, </C1>]
    prepend apiSchemas = "CollectionAPI"
    delete apiSchemas = ["Old"]
    append specializes = </S>
)
{
}
)");
    ASSERT_TRUE(layer);
    const PrimSpec& p = *layer->pseudoRoot.child("P");
    EXPECT_FALSE(p.references.explicitItems);
    ASSERT_EQ(p.references.prepended.size(), 1u);
    EXPECT_EQ(p.references.prepended[0].assetPath, "a.usda");
    EXPECT_EQ(p.references.prepended[0].primPath, "/A");
    EXPECT_EQ(p.references.prepended[0].where.line, 3);
    EXPECT_EQ(p.references.prepended[0].where.column, 26);
    ASSERT_EQ(p.references.appended.size(), 2u);
    EXPECT_EQ(p.references.appended[0].assetPath, "b.usda");
    EXPECT_EQ(p.references.appended[0].primPath, "");
    EXPECT_EQ(p.references.appended[1].assetPath, "");
    EXPECT_EQ(p.references.appended[1].primPath, "/Internal");
    ASSERT_EQ(p.references.deleted.size(), 1u);
    EXPECT_EQ(p.references.deleted[0].assetPath, "c.usda");
    ASSERT_EQ(p.payloads.added.size(), 1u);
    EXPECT_EQ(p.payloads.added[0].primPath, "/P");
    ASSERT_EQ(p.inherits.ordered.size(), 2u);
    EXPECT_EQ(p.inherits.ordered[0].primPath, "/C2");
    EXPECT_EQ(p.apiSchemas.prepended, std::vector<std::string>{"CollectionAPI"});
    EXPECT_EQ(p.apiSchemas.deleted, std::vector<std::string>{"Old"});
    ASSERT_EQ(p.specializes.appended.size(), 1u);
    EXPECT_EQ(p.specializes.appended[0].primPath, "/S");
}

TEST(ParserSyntax, AttributesDeclarationsAndQualifiers) {
    const auto stage = open(R"(#usda 1.0
def Mesh "M"
{
    custom uniform token[] tags = ["a"]
    uniform token subdivisionScheme = "none"
    varying float v = 1
    config int legacy = 2
    float declaredOnly
    custom double customOnly
    texCoord2f[] primvars:st = [(0, 0)] (
        interpolation = "faceVarying"
        elementSize = 2
        doc = "uv set"
    )
    float inputs:opacity = 1 (interpolation = "constant"; customData = { int x = 1 })
    float a = 1; float b = 2
}
)");
    ASSERT_TRUE(stage);
    const Prim& m = *stage->find("/M");
    const Attribute& tags = *m.attribute("tags");
    EXPECT_TRUE(tags.isCustom);
    EXPECT_TRUE(tags.isUniform);
    EXPECT_EQ(tags.typeName, "uniform token[]");
    EXPECT_EQ(m.attribute("subdivisionScheme")->typeName, "uniform token");
    EXPECT_FALSE(m.attribute("v")->isUniform);
    EXPECT_TRUE(m.attribute("legacy")->isUniform);
    EXPECT_FALSE(m.attribute("declaredOnly")->defaultValue);
    EXPECT_TRUE(m.attribute("customOnly")->isCustom);
    const Attribute& st = *m.attribute("primvars:st");
    EXPECT_EQ(st.metadata.at("interpolation").strings.at(0), "faceVarying");
    EXPECT_EQ(st.metadata.at("elementSize").numbers.at(0), 2.0);
    EXPECT_EQ(st.metadata.at("documentation").strings.at(0), "uv set");
    EXPECT_EQ(m.attribute("inputs:opacity")->metadata.at("interpolation").strings.at(0), "constant");
    EXPECT_EQ(m.attribute("inputs:opacity")->metadata.at("customData:x").numbers.at(0), 1.0);
    EXPECT_EQ(defaultOf(*stage, "/M", "a").numbers.at(0), 1.0);
    EXPECT_EQ(defaultOf(*stage, "/M", "b").numbers.at(0), 2.0);
    EXPECT_EQ(st.where.line, 10);
}

TEST(ParserSyntax, TimeSamples) {
    const auto stage = open(R"(#usda 1.0
def Xform "X"
{
    double3 xformOp:translate = (9, 9, 9)
    double3 xformOp:translate.timeSamples = {
        -10: (0, 0, 0),
        0.5: (1, 2, 3),
        1e2: (4, 5, 6),
    }
    float compact.timeSamples = { 1: 1, 2: None, 3: 3 }
    float[] arrays.timeSamples = {
        0: [1, 2],
        1: [],
    }
    token empty.timeSamples = {}
}
)");
    ASSERT_TRUE(stage);
    const Attribute& translate = *stage->find("/X")->attribute("xformOp:translate");
    ASSERT_TRUE(translate.defaultValue);
    EXPECT_EQ(translate.defaultValue->numbers, (std::vector<double>{9, 9, 9}));
    ASSERT_EQ(translate.timeSamples.size(), 3u);
    EXPECT_EQ(translate.timeSamples.at(-10).numbers, (std::vector<double>{0, 0, 0}));
    EXPECT_EQ(translate.timeSamples.at(0.5).numbers, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(translate.timeSamples.at(100).typeName, "double3");
    EXPECT_TRUE(translate.isAnimated());
    const Attribute& compact = *stage->find("/X")->attribute("compact");
    ASSERT_EQ(compact.timeSamples.size(), 3u);
    EXPECT_TRUE(compact.timeSamples.at(2).blocked);
    EXPECT_FALSE(compact.timeSamples.at(3).blocked);
    const Attribute& arrays = *stage->find("/X")->attribute("arrays");
    EXPECT_EQ(arrays.timeSamples.at(0).size(), 2u);
    EXPECT_EQ(arrays.timeSamples.at(1).size(), 0u);
    EXPECT_TRUE(arrays.timeSamples.at(1).isArray);
    EXPECT_TRUE(stage->find("/X")->attribute("empty")->timeSamples.empty());
}

TEST(ParserSyntax, Connections) {
    const auto stage = open(R"(#usda 1.0
def Material "Mat"
{
    token outputs:surface.connect = </Mat/Surface.outputs:surface>
    color3f inputs:tint.connect = <Tex.outputs:rgb>
    float inputs:x.connect = [<../Mat/Surface.outputs:x>]
    float inputs:y = 0.5
    prepend float inputs:y.connect = </Mat/Y.outputs:out>
    float inputs:none.connect = None
}
)");
    ASSERT_TRUE(stage);
    const Prim& mat = *stage->find("/Mat");
    EXPECT_EQ(mat.attribute("outputs:surface")->connection, "/Mat/Surface.outputs:surface");
    EXPECT_EQ(mat.attribute("inputs:tint")->connection, "/Mat/Tex.outputs:rgb");
    EXPECT_EQ(mat.attribute("inputs:x")->connection, "/Mat/Surface.outputs:x");
    EXPECT_EQ(mat.attribute("inputs:y")->connection, "/Mat/Y.outputs:out");
    EXPECT_EQ(defaultOf(*stage, "/Mat", "inputs:y").numbers.at(0), 0.5);
    EXPECT_FALSE(mat.attribute("inputs:none")->connection);
}

// OpenUSD 25.05's splines and AnimationBlock: a spline as Sdf_FileIOUtility::WriteSpline writes
// it is read whole (custom data included); one on a type no spline animates warns, naming the
// attribute, which keeps its default; AnimationBlock authors no default.
TEST(ParserSyntax, SplinesAreReadAndAnimationBlockAuthorsNoDefault) {
    const auto stage = open(R"(#usda 1.0
def Xform "A"
{
    double x = 2
    varying double x.spline = {
        bezier,
        pre: linear,
        post: sloped(0.57),
        loop: (15, 25, 0, 2, 11.7),
        7: 5.5 & 7.21; post held,
        15: 8.18; post curve ws(2.49, 1.17); { string comment = "climb!" },
        20: 14.72; pre ws(3.77, -1.4); post curve ws(1.1, -1.4),
    }
    float3 v = (1, 2, 3)
    float3 v.spline = { 1: 2 }
    float y = AnimationBlock
    float z = 3
}
)");
    ASSERT_TRUE(stage);
    const Prim& a = *stage->find("/A");
    EXPECT_EQ(defaultOf(*stage, "/A", "x").numbers.at(0), 2.0);
    const Spline& x = *a.attribute("x")->spline;
    EXPECT_EQ(x.valueType, "double");
    EXPECT_EQ(x.pre.mode, SplineExtrapolationMode::Linear);
    EXPECT_EQ(x.post.mode, SplineExtrapolationMode::Sloped);
    EXPECT_EQ(x.post.slope, 0.57);
    EXPECT_EQ(x.loop, (SplineLoop{15, 25, 0, 2, 11.7}));
    ASSERT_EQ(x.knots.size(), 3u);
    EXPECT_EQ(x.knots[0].preValue, 5.5);
    EXPECT_EQ(x.knots[0].value, 7.21);
    EXPECT_EQ(x.knots[1].next, SplineInterpolation::Curve);
    EXPECT_EQ(x.knots[1].postWidth, 2.49);
    EXPECT_EQ(x.knots[2].preSlope, -1.4);
    EXPECT_FALSE(a.attribute("v")->spline);
    EXPECT_EQ(defaultOf(*stage, "/A", "v").numbers.at(2), 3.0);
    EXPECT_FALSE(a.attribute("y")->defaultValue);
    EXPECT_EQ(defaultOf(*stage, "/A", "z").numbers.at(0), 3.0);
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_EQ(stage->warnings()[0].where.line, 15);
    EXPECT_EQ(stage->warnings()[0].message,
              "attribute 'v' of </A> is a float3, which no spline animates (double, float, half and timecode do); its "
              "default and time samples are used");
}

// Opaque attributes (and groups, which are opaque) hold no value: they are declared and connected,
// as UsdShade writes a shader's struct-like outputs.
TEST(ParserSyntax, OpaqueAttributesAreDeclaredAndConnected) {
    const auto stage = open(R"(#usda 1.0
def Shader "S"
{
    opaque outputs:out
    opaque inputs:in.connect = </S.outputs:out>
    group inputs:options
}
)");
    ASSERT_TRUE(stage);
    const Prim& s = *stage->find("/S");
    ASSERT_NE(s.attribute("outputs:out"), nullptr);
    EXPECT_FALSE(s.attribute("outputs:out")->defaultValue);
    EXPECT_EQ(s.attribute("inputs:in")->connection, "/S.outputs:out");
    ASSERT_NE(s.attribute("inputs:options"), nullptr);
}

TEST(ParserSyntax, Relationships) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    rel single = </A/B>
    rel many = [</A>, </B.prop>, <Child>, <../Sibling>]
    rel declared
    custom rel customRel = None
    rel empty = []
    prepend rel material:binding = </Looks/M>
    rel withMeta = </A> (
        doc = "documented"
    )
}
)");
    ASSERT_TRUE(stage);
    const Prim& p = *stage->find("/P");
    EXPECT_EQ(p.relationship("single")->targets, std::vector<std::string>{"/A/B"});
    EXPECT_EQ(p.relationship("many")->targets,
              (std::vector<std::string>{"/A", "/B.prop", "/P/Child", "/Sibling"}));
    ASSERT_TRUE(p.relationship("declared"));
    EXPECT_TRUE(p.relationship("declared")->targets.empty());
    EXPECT_TRUE(p.relationship("customRel")->targets.empty());
    EXPECT_TRUE(p.relationship("empty")->targets.empty());
    EXPECT_EQ(p.relationship("material:binding")->targets, std::vector<std::string>{"/Looks/M"});
    EXPECT_EQ(p.relationship("withMeta")->targets, std::vector<std::string>{"/A"});
    EXPECT_EQ(p.relationship("withMeta")->name, "withMeta");
}

TEST(ParserSyntax, CommentsAnywhere) {
    const auto stage = open(R"(#usda 1.0
# leading comment
( # after paren
    upAxis = "Z" // trailing
    /* block
       comment */ metersPerUnit = 2
)
// between prims
def "P" ( kind = "component" /* inline */ ) # after metadata
{ # after brace
    float a = 1 # after value
    float[] b = [1, /* inside */ 2] // done
    /* a block comment swallows its newlines */ float c = 3
}
# trailing)");
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->metadata().upAxis, "Z");
    EXPECT_EQ(stage->metadata().metersPerUnit, 2.0);
    EXPECT_EQ(defaultOf(*stage, "/P", "b").numbers, (std::vector<double>{1, 2}));
    EXPECT_EQ(defaultOf(*stage, "/P", "c").numbers.at(0), 3.0);
    EXPECT_EQ(stage->find("/P")->kind, "component");
}

TEST(ParserSyntax, NamespacedAndKeywordNames) {
    const auto stage = open(R"(#usda 1.0
def "P"
{
    float xformOp:rotateXYZ:pivot = 1
    float inputs:diffuseColor = 1
    float class = 2
    rel over = </X>
    float def:rel = 3
}
)");
    ASSERT_TRUE(stage);
    const Prim& p = *stage->find("/P");
    EXPECT_TRUE(p.attribute("xformOp:rotateXYZ:pivot"));
    EXPECT_TRUE(p.attribute("inputs:diffuseColor"));
    EXPECT_TRUE(p.attribute("class"));
    EXPECT_TRUE(p.relationship("over"));
    EXPECT_TRUE(p.attribute("def:rel"));
}

TEST(ParserSyntax, VariantSetsAreParsed) {
    const auto layer = parse(R"(#usda 1.0
def "P" (
    variants = {
        string lod = "high"
        string color = "red"
    }
    prepend variantSets = ["lod", "color"]
)
{
    variantSet "lod" = {
        "high" (
            kind = "component"
        ) {
            def Sphere "Ball"
            {
            }
        }
        "low" {
            float detail = 0
        }
    }
}
)");
    ASSERT_TRUE(layer);
    const PrimSpec& p = *layer->pseudoRoot.child("P");
    EXPECT_EQ(p.variantSelections.at("lod"), "high");
    EXPECT_EQ(p.variantSelections.at("color"), "red");
    const VariantSetSpec& lod = p.variantSets.at("lod");
    ASSERT_EQ(lod.variants.size(), 2u);
    EXPECT_EQ(lod.variants.at("high")->metadata.at("kind").strings.at(0), "component");
    EXPECT_TRUE(lod.variants.at("high")->child("Ball"));
    EXPECT_TRUE(lod.variants.at("low")->attributes.count("detail"));
    EXPECT_EQ(layer->find("/P{lod=high}/Ball")->typeName, "Sphere");
    EXPECT_EQ(layer->find("/P{lod=missing}"), nullptr);
}

TEST(ParserSyntax, IgnoredStatementsWarnOncePerKind) {
    const auto ok = open(R"(#usda 1.0
reorder rootPrims = ["B", "A"]
def "A"
{
    reorder nameChildren = ["y", "x"]
    reorder properties = ["b"]
}
)");
    ASSERT_TRUE(ok);
    ASSERT_EQ(ok->warnings().size(), 1u);
    EXPECT_NE(ok->warnings()[0].message.find("reorder"), std::string::npos);
    EXPECT_EQ(ok->warnings()[0].where.line, 2);
}

TEST(ParserSyntax, UnexpectedVersionWarns) {
    const auto stage = open("#usda 1.1\n");
    ASSERT_TRUE(stage);
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_NE(stage->warnings()[0].message.find("1.1"), std::string::npos);
}

TEST(ParserSyntax, WindowsLineEndings) {
    const auto stage = open("#usda 1.0\r\ndef \"P\"\r\n{\r\n    float a = 1\r\n    float b = 2\r\n}\r\n");
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->find("/P")->attribute("b")->where.line, 5);
}

}  // namespace
}  // namespace obscura::usda
