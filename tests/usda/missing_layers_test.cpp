// Arcs and sublayers whose layer is missing or cannot be read (its syntax, a crate file's bytes, a
// package or an entry of one): as Pcp reports them, each is one warning where the arc is authored,
// naming the asset and why (a syntax error with its own file, line and column); the arc adds
// nothing and the rest of the stage composes. Only the root layer itself stops the stage.
#include <algorithm>
#include <filesystem>
#include <sstream>

#include "tests/support/usdz_files.h"
#include "tests/usda/crate_writer.h"
#include "tests/usda/usda_test_util.h"

namespace obscura::usda::test {
namespace {

namespace fs = std::filesystem;
using obscura::test::writeUsdz;

// Where `marker` first appears in `text` (after `after`), the layer at `file`: its line and column,
// from 1.
SourceLocation whereIs(const std::string& file, const std::string& text, const std::string& marker,
                       const std::string& after = "") {
    const size_t at = text.find(marker, text.find(after));
    if (at == std::string::npos) {
        ADD_FAILURE() << "no '" << marker << "' in " << file;
        return {};
    }
    const size_t lineStart = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
    return SourceLocation{file, 1 + int(std::count(text.begin(), text.begin() + long(at), '\n')),
                          1 + int(at - lineStart)};
}

// The stage gives the warning `message` once, at `where`.
void expectWarning(const Stage& stage, const std::string& message, const SourceLocation& where) {
    const std::vector<Warning>& warnings = stage.warnings();
    auto isIt = [&](const Warning& w) { return w.message == message; };
    const auto it = std::find_if(warnings.begin(), warnings.end(), isIt);
    if (it == warnings.end()) {
        std::ostringstream given;
        for (const Warning& w : warnings) given << "\n  " << w.where.file << ":" << w.where.line << ": " << w.message;
        ADD_FAILURE() << "no warning '" << message << "'; the stage warns:" << given.str();
        return;
    }
    EXPECT_EQ(it->where.file, where.file) << message;
    EXPECT_EQ(it->where.line, where.line) << message;
    EXPECT_EQ(it->where.column, where.column) << message;
    EXPECT_EQ(std::count_if(warnings.begin(), warnings.end(), isIt), 1) << message;
}

double xOf(const Stage& stage, const std::string& path) {
    const Prim* prim = stage.find(path);
    const Attribute* x = prim ? prim->attribute("x") : nullptr;
    if (!x || !x->defaultValue || x->defaultValue->numbers.empty()) {
        ADD_FAILURE() << "no x on " << path;
        return 0;
    }
    return x->defaultValue->numbers[0];
}

const std::string kAsset = "#usda 1.0\n(\n    defaultPrim = \"Asset\"\n)\ndef \"Asset\"\n{\n    double x = 2\n"
                           "    def \"Leg\"\n    {\n    }\n}\n";
const std::string kBroken = "#usda 1.0\ndef \"Broken\"\n{\n    float x = \n}\n";
const std::string kBrokenError = ":4:15: expected a number for float, found end of line";

TEST(MissingLayers, ReferencesAndPayloadsToMissingFilesWarnWhereAuthoredAndTheRestComposes) {
    const std::string root = R"(#usda 1.0
def "World"
{
    def "Chair" (
        references = @gone.usda@
        payload = @gone_payload.usda@</P>
    )
    {
        double x = 1
        def "Cushion"
        {
        }
    }
    def "Table" (
        references = @asset.usda@
    )
    {
    }
}
)";
    LayerFiles files({{"root.usda", root}, {"asset.usda", kAsset}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    const std::string rootPath = files.path("root.usda");
    expectWarning(*stage,
                  "reference of </World/Chair> to @gone.usda@ ignored: " + files.path("gone.usda") + ": no such file",
                  whereIs(rootPath, root, "@gone.usda@"));
    expectWarning(*stage,
                  "payload of </World/Chair> to @gone_payload.usda@ ignored: " + files.path("gone_payload.usda") +
                      ": no such file",
                  whereIs(rootPath, root, "@gone_payload.usda@"));
    // The broken arcs' prim keeps its own opinions; the other arcs compose.
    EXPECT_EQ(xOf(*stage, "/World/Chair"), 1);
    EXPECT_TRUE(stage->find("/World/Chair/Cushion"));
    EXPECT_EQ(xOf(*stage, "/World/Table"), 2);
    EXPECT_TRUE(stage->find("/World/Table/Leg"));
}

TEST(MissingLayers, AMissingOrUnreadableSublayerWarnsWhereItIsListedAndTheOtherLayersCompose) {
    const std::string root = R"(#usda 1.0
(
    subLayers = [
        @gone.usda@,
        @folder@,
        @strong.usda@
    ]
)
def "A"
{
    double x = 1
}
)";
    LayerFiles files({{"root.usda", root}, {"strong.usda", "#usda 1.0\ndef \"B\"\n{\n    double x = 2\n}\n"}});
    fs::create_directories(files.path("folder"));
    auto stage = files.open();
    ASSERT_TRUE(stage);
    const std::string rootPath = files.path("root.usda");
    expectWarning(*stage, "sublayer @gone.usda@ ignored: " + files.path("gone.usda") + ": no such file",
                  whereIs(rootPath, root, "@gone.usda@"));
    expectWarning(*stage, "sublayer @folder@ ignored: " + files.path("folder") + ": cannot be read",
                  whereIs(rootPath, root, "@folder@"));
    EXPECT_EQ(xOf(*stage, "/A"), 1);
    EXPECT_EQ(xOf(*stage, "/B"), 2);
}

// As OpenUSD: a layer with a syntax error does not open; the arcs to it report the error, with its
// own location, and add nothing.
TEST(MissingLayers, ALayerThatDoesNotParseIsReportedWithItsErrorAtEachArcAndAddsNothing) {
    const std::string root = R"(#usda 1.0
(
    subLayers = [
        @broken.usda@
    ]
)
def "A" (
    references = @broken.usda@
)
{
    double x = 1
}
def "B" (
    references = @asset.usda@
)
{
}
)";
    LayerFiles files({{"root.usda", root}, {"asset.usda", kAsset}, {"broken.usda", kBroken}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    const std::string rootPath = files.path("root.usda");
    const std::string why = files.path("broken.usda") + kBrokenError;
    expectWarning(*stage, "sublayer @broken.usda@ ignored: " + why, whereIs(rootPath, root, "@broken.usda@"));
    expectWarning(*stage, "reference of </A> to @broken.usda@ ignored: " + why,
                  whereIs(rootPath, root, "@broken.usda@", "references"));
    EXPECT_EQ(xOf(*stage, "/A"), 1);
    EXPECT_FALSE(stage->find("/Broken"));
    EXPECT_EQ(xOf(*stage, "/B"), 2);
    EXPECT_TRUE(stage->find("/B/Leg"));
}

// Each arc reports its asset once: two arcs to one missing file report twice, an arc inside an
// asset referenced twice once.
TEST(MissingLayers, EachArcReportsItsAssetOnce) {
    const std::string root = R"(#usda 1.0
def "A" (
    references = @gone.usda@
)
{
}
def "B" (
    prepend references = @gone.usda@
)
{
}
def "C" (
    references = @asset.usda@
)
{
}
def "D" (
    references = @asset.usda@
)
{
}
)";
    const std::string asset = "#usda 1.0\n(\n    defaultPrim = \"Asset\"\n)\n"
                              "def \"Asset\" (\n    references = @gone.usda@\n)\n{\n    double x = 2\n}\n";
    LayerFiles files({{"root.usda", root}, {"asset.usda", asset}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    const std::string rootPath = files.path("root.usda");
    const std::string why = "@gone.usda@ ignored: " + files.path("gone.usda") + ": no such file";
    expectWarning(*stage, "reference of </A> to " + why, whereIs(rootPath, root, "@gone.usda@"));
    expectWarning(*stage, "reference of </B> to " + why, whereIs(rootPath, root, "@gone.usda@", "prepend"));
    expectWarning(*stage, "reference of </Asset> to " + why, whereIs(files.path("asset.usda"), asset, "@gone.usda@"));
    EXPECT_EQ(stage->warnings().size(), 3u);
    EXPECT_EQ(xOf(*stage, "/C"), 2);
    EXPECT_EQ(xOf(*stage, "/D"), 2);
}

// Classes in a sublayer that is missing: the sublayer and each class arc that finds nothing are
// reported, each where it is authored; the prim keeps its own opinions.
TEST(MissingLayers, InheritsAndSpecializesIntoAMissingSublayerWarnEachAtItsArc) {
    const std::string root = R"(#usda 1.0
(
    subLayers = [
        @classes.usda@
    ]
)
def "Prim" (
    inherits = </Class>
    specializes = </Base>
)
{
    double x = 1
}
)";
    LayerFiles files({{"root.usda", root}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    const std::string rootPath = files.path("root.usda");
    expectWarning(*stage, "sublayer @classes.usda@ ignored: " + files.path("classes.usda") + ": no such file",
                  whereIs(rootPath, root, "@classes.usda@"));
    expectWarning(*stage, "</Class> not found in '" + rootPath + "'; arc ignored", whereIs(rootPath, root, "</Class>"));
    expectWarning(*stage, "</Base> not found in '" + rootPath + "'; arc ignored", whereIs(rootPath, root, "</Base>"));
    EXPECT_EQ(xOf(*stage, "/Prim"), 1);
}

TEST(MissingLayers, AReferenceToALayerWithoutPrimsWarnsAndAddsNothing) {
    const std::string root = "#usda 1.0\ndef \"A\" (\n    references = @empty.usda@\n)\n{\n    double x = 1\n}\n";
    LayerFiles files({{"root.usda", root}, {"empty.usda", "#usda 1.0\n"}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    expectWarning(*stage, "layer '" + files.path("empty.usda") + "' has no prim to reference; arc ignored",
                  whereIs(files.path("root.usda"), root, "@empty.usda@"));
    EXPECT_EQ(xOf(*stage, "/A"), 1);
}

// A crate layer's arcs and sublayers report as a text layer's do, at the file (a crate file has no
// lines) with the prim they are authored on; a crate file that does not read is reported with the
// byte its problem concerns.
TEST(MissingLayers, CrateLayersReportArcsToMissingLayersAndAreReportedWhenTheyDoNotRead) {
    CrateWriter writer;
    const uint64_t subLayers = writer.stored(
        crate::Type::StringVector, CrateWriter::raw<uint64_t>(1) + CrateWriter::raw(writer.string("gone_sub.usda")));
    // A prepended reference (SdfListOp bit 32): asset, prim </A>, layer offset, empty customData.
    const uint64_t references = writer.stored(
        crate::Type::ReferenceListOp,
        std::string(1, char(32)) + CrateWriter::raw<uint64_t>(1) + CrateWriter::raw(writer.string("gone.usda")) +
            CrateWriter::raw(CrateWriter::kPrimA) + CrateWriter::raw(0.0) + CrateWriter::raw(1.0) +
            CrateWriter::raw<uint64_t>(0));
    const uint64_t doubleType = CrateWriter::inlined(crate::Type::Token, writer.token("double"));
    const std::string crate =
        writer.write({{"x", {{"typeName", doubleType}, {"default", CrateWriter::inlined(crate::Type::Double, 0)}}}},
                     {{"subLayers", subLayers}}, {{"references", references}});
    const std::string root = "#usda 1.0\ndef \"Binary\" (\n    references = @binary.usdc@</A>\n)\n{\n}\n"
                             "def \"Corrupt\" (\n    references = @corrupt.usdc@\n)\n{\n    double x = 1\n}\n";
    LayerFiles files(
        {{"root.usda", root}, {"binary.usdc", crate}, {"corrupt.usdc", "PXR-USDC" + std::string(8, '\0')}});
    auto stage = files.open();
    ASSERT_TRUE(stage);
    const SourceLocation inCrate{files.path("binary.usdc"), 0, 0};
    expectWarning(*stage, "sublayer @gone_sub.usda@ ignored: " + files.path("gone_sub.usda") + ": no such file",
                  inCrate);
    expectWarning(*stage, "reference of </A> to @gone.usda@ ignored: " + files.path("gone.usda") + ": no such file",
                  inCrate);
    expectWarning(*stage,
                  "reference of </Corrupt> to @corrupt.usdc@ ignored: " + files.path("corrupt.usdc") +
                      ": byte 0: file of 16 bytes is too short for the crate header",
                  whereIs(files.path("root.usda"), root, "@corrupt.usdc@"));
    EXPECT_EQ(xOf(*stage, "/Binary"), 0);  // the crate's own opinion, through the reference
    EXPECT_EQ(xOf(*stage, "/Corrupt"), 1);
}

// Inside a package, arcs to entries it does not hold or that do not parse report as files do; arcs
// to packages that are missing, not zip archives, or hold no layer report the package's problem.
TEST(MissingLayers, ArcsInAndToPackagesReportWhatCannotBeRead) {
    const std::string scene = R"(#usda 1.0
(
    subLayers = [
        @missing_sub.usda@
    ]
)
def "A" (
    references = @missing.usda@
)
{
    double x = 1
}
def "B" (
    references = @broken.usda@
)
{
}
def "C" (
    references = @asset.usda@
)
{
}
)";
    const std::string root = R"(#usda 1.0
def "Packaged" (
    references = @scene.usdz@</C>
)
{
}
def "NoPackage" (
    references = @nothing.usdz@</A>
)
{
}
def "NotAZip" (
    references = @not_a_zip.usdz[scene.usda]@</A>
)
{
}
def "NoLayer" (
    references = @textures.usdz@</A>
)
{
    double x = 3
}
)";
    LayerFiles files({{"root.usda", root}, {"not_a_zip.usdz", "PK\x03\x04 is all there is"}});
    ASSERT_EQ(writeUsdz(files.path("scene.usdz"),
                           {{"scene.usda", scene}, {"broken.usda", kBroken}, {"asset.usda", kAsset}}),
              "");
    ASSERT_EQ(writeUsdz(files.path("textures.usdz"), {{"a.png", "not a layer"}}), "");

    // The package as the stage.
    auto packaged = openFile(files.path("scene.usdz"));
    ASSERT_TRUE(packaged);
    const std::string package = files.path("scene.usdz");
    const std::string layer = package + "[scene.usda]";
    expectWarning(*packaged,
                  "sublayer @missing_sub.usda@ ignored: " + package + ": no file 'missing_sub.usda' in the package",
                  whereIs(layer, scene, "@missing_sub.usda@"));
    expectWarning(*packaged,
                  "reference of </A> to @missing.usda@ ignored: " + package + ": no file 'missing.usda' in the package",
                  whereIs(layer, scene, "@missing.usda@"));
    expectWarning(*packaged, "reference of </B> to @broken.usda@ ignored: " + package + "[broken.usda]" + kBrokenError,
                  whereIs(layer, scene, "@broken.usda@"));
    EXPECT_EQ(xOf(*packaged, "/A"), 1);
    EXPECT_EQ(xOf(*packaged, "/C"), 2);
    EXPECT_TRUE(packaged->find("/C/Leg"));

    // Arcs to packages.
    auto stage = files.open();
    ASSERT_TRUE(stage);
    const std::string rootPath = files.path("root.usda");
    expectWarning(*stage,
                  "reference of </NoPackage> to @nothing.usdz@ ignored: " + files.path("nothing.usdz") +
                      ": no such file",
                  whereIs(rootPath, root, "@nothing.usdz@"));
    const auto notAZip = std::find_if(stage->warnings().begin(), stage->warnings().end(), [](const Warning& w) {
        return w.message.find("@not_a_zip.usdz[scene.usda]@ ignored: ") != std::string::npos;
    });
    ASSERT_NE(notAZip, stage->warnings().end());
    EXPECT_NE(notAZip->message.find(files.path("not_a_zip.usdz") + ": not a readable zip archive"), std::string::npos)
        << notAZip->message;
    expectWarning(*stage,
                  "reference of </NoLayer> to @textures.usdz@ ignored: " + files.path("textures.usdz") +
                      ": the package holds no .usd, .usda or .usdc layer",
                  whereIs(rootPath, root, "@textures.usdz@"));
    EXPECT_EQ(xOf(*stage, "/NoLayer"), 3);
    EXPECT_EQ(xOf(*stage, "/Packaged"), 2);  // the package's own warnings come along
    EXPECT_TRUE(stage->find("/Packaged/Leg"));
}

// The root layer is the stage: one that cannot be read is still an error, at its syntax error.
TEST(MissingLayers, TheRootLayerItselfStaysAnError) {
    LayerFiles files({{"root.usda", kBroken}});
    auto result = Stage::open(files.path("root.usda"));
    ASSERT_TRUE(std::holds_alternative<Error>(result));
    EXPECT_EQ(std::get<Error>(result).str(), files.path("root.usda") + kBrokenError);
    ASSERT_EQ(writeUsdz(files.path("root.usdz"), {{"root.usda", kBroken}}), "");
    result = Stage::open(files.path("root.usdz"));
    ASSERT_TRUE(std::holds_alternative<Error>(result));
    EXPECT_EQ(std::get<Error>(result).str(), files.path("root.usdz") + "[root.usda]" + kBrokenError);
}

}  // namespace
}  // namespace obscura::usda::test
