// The crate (.usdc) reader and USDZ packages: integer coding against hand-computed vectors,
// real crate files from the corpus (shared/corpus, files written by OpenUSD) checked against facts
// that hold independently of the reader (an authored extent bounds the points it was computed
// from, topology indexes its points, a text layer of the same asset family has the same schema),
// a package compared prim by prim with the text scene it was made from, and malformed files.
#include <gtest/gtest.h>
#include <lz4.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "assets/asset_reader.h"
#include "assets/package_path.h"
#include "harness/usda/crate_compression.h"
#include "tests/support/usdz_files.h"
#include "usda_test_util.h"

namespace obscura::usda::test {
namespace {

namespace fs = std::filesystem;
using crate::Failure;

const fs::path kCorpus = OBSCURA_CORPUS_DIR;
const fs::path kChess = kCorpus / "full_assets/OpenChessSet";
const fs::path kRigged = kCorpus / "test_assets/USDZ/RiggedSimple/RiggedSimple.usdz";
const fs::path kNormals = kCorpus / "test_assets/NormalsTextureBiasAndScale";

#define REQUIRE_CORPUS()                                                                       \
    if (!fs::exists(kCorpus)) GTEST_SKIP() << "no corpus at " << kCorpus << " (shared/corpus beside the checkout)"

std::string bytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

template <class T>
std::string raw(T value) {
    return std::string(reinterpret_cast<const char*>(&value), sizeof(T));
}

// ---- Integer coding ---------------------------------------------------------------------------

// The example of integerCoding.cpp: deltas [123, 1, 1, 100000, 0, 1, 0], most common delta 1.
// Codes (2 bits each, first value lowest): 01 00 00 11 | 01 00 01 -> 0xC1, 0x11.
std::string integerCodingExample() {
    return raw<int32_t>(1) + "\xC1\x11" + raw<int8_t>(123) + raw<int32_t>(100000) + raw<int8_t>(0) + raw<int8_t>(0);
}

TEST(CrateIntegers, DecodesTheDocumentedExample) {
    const std::string encoded = integerCodingExample();
    EXPECT_EQ(crate::decodeIntegers<int32_t>(encoded, 7, 0),
              (std::vector<int32_t>{123, 124, 125, 100125, 100125, 100126, 100126}));
}

TEST(CrateIntegers, SixtyFourBitCodesUseWiderDeltas) {
    // [5, -3]: deltas 5 (the common value, code 00) and -8 (code 01: int16 for 64-bit ints).
    const std::string encoded = raw<int64_t>(5) + "\x04" + raw<int16_t>(-8);
    EXPECT_EQ(crate::decodeIntegers<int64_t>(encoded, 2, 0), (std::vector<int64_t>{5, -3}));
    // 16-bit deltas of 32-bit ints (code 10) and a negative running sum read as unsigned.
    const std::string medium = raw<int32_t>(0) + "\x0A" + raw<int16_t>(-300) + raw<int16_t>(1000);
    EXPECT_EQ(crate::decodeIntegers<int32_t>(medium, 2, 0), (std::vector<int32_t>{-300, 700}));
    EXPECT_EQ(crate::decodeIntegers<uint32_t>(medium, 2, 0), (std::vector<uint32_t>{4294966996u, 700}));
}

TEST(CrateIntegers, DecompressesThroughLz4) {
    const std::string encoded = integerCodingExample();
    std::string compressed(LZ4_compressBound(static_cast<int>(encoded.size())) + 1, '\0');
    compressed[0] = 0;  // one chunk
    const int size = LZ4_compress_default(encoded.data(), compressed.data() + 1, static_cast<int>(encoded.size()),
                                          static_cast<int>(compressed.size() - 1));
    compressed.resize(static_cast<size_t>(size) + 1);
    EXPECT_EQ(crate::decompressIntegers<uint32_t>(compressed, 7, 0),
              (std::vector<uint32_t>{123, 124, 125, 100125, 100125, 100126, 100126}));
}

TEST(CrateIntegers, MalformedStreamsFailAtTheirOffset) {
    const std::string encoded = integerCodingExample();
    try {
        crate::decodeIntegers<int32_t>(encoded.substr(0, 8), 7, 1234);
        FAIL() << "truncated values decoded";
    } catch (const Failure& failure) {
        EXPECT_EQ(failure.offset, 1234u);
        EXPECT_NE(failure.message.find("end before their values"), std::string::npos) << failure.message;
    }
    EXPECT_THROW(crate::decompressIntegers<int32_t>(std::string("\0\xFF\xFF", 3), 7, 0), Failure);
    // A count no compressed block of this size can hold is refused before anything is allocated.
    EXPECT_THROW(crate::decompressIntegers<int32_t>(std::string(4, '\0'), size_t(1) << 40, 0), Failure);
}

// ---- Corpus crate files -------------------------------------------------------------------------

const std::vector<std::string> kCratePieces = {"Bishop", "Chessboard", "King", "Pawn", "Queen", "Rook"};

std::vector<double> numbers(const Prim& prim, const std::string& name) {
    const Attribute* attr = prim.attribute(name);
    if (!attr || !attr->defaultValue) return {};
    return attr->defaultValue->numbers;
}

// Topology and extent of every mesh: indexes address points, face sizes add up to the index
// count, an authored extent bounds the points (and, where `exactExtents`, is their bounding box:
// the exporter computed it from them; the Pawn's two meshes share one extent of both).
void expectValidMeshes(const Stage& stage, size_t* meshCount, bool exactExtents = false) {
    for (const Prim* prim : stage.prims()) {
        if (prim->typeName != "Mesh") continue;
        ++*meshCount;
        const auto points = numbers(*prim, "points");
        const auto counts = numbers(*prim, "faceVertexCounts");
        const auto indices = numbers(*prim, "faceVertexIndices");
        ASSERT_FALSE(points.empty()) << prim->path;
        ASSERT_EQ(points.size() % 3, 0u);
        double corners = 0;
        for (double c : counts) corners += c;
        EXPECT_EQ(corners, double(indices.size())) << prim->path;
        for (double i : indices) ASSERT_TRUE(i >= 0 && i < double(points.size() / 3)) << prim->path;
        const auto extent = numbers(*prim, "extent");
        if (extent.size() == 6) {
            for (int axis = 0; axis < 3; ++axis) {
                double low = INFINITY, high = -INFINITY;
                for (size_t p = axis; p < points.size(); p += 3) {
                    low = std::min(low, points[p]);
                    high = std::max(high, points[p]);
                }
                EXPECT_LE(extent[axis], low) << prim->path << " axis " << axis;
                EXPECT_GE(extent[3 + axis], high) << prim->path << " axis " << axis;
                if (exactExtents) {
                    EXPECT_EQ(extent[axis], low) << prim->path << " axis " << axis;
                    EXPECT_EQ(extent[3 + axis], high) << prim->path << " axis " << axis;
                }
            }
        }
        if (const Attribute* st = prim->attribute("primvars:st"); st && st->defaultValue) {
            auto interpolation = st->metadata.find("interpolation");
            ASSERT_NE(interpolation, st->metadata.end());
            if (interpolation->second.strings.at(0) == "faceVarying") {
                EXPECT_EQ(st->defaultValue->size(), indices.size()) << prim->path;
            }
        }
    }
}

TEST(CrateCorpus, GeometryLayersReadWithConsistentTopologyAndExtents) {
    REQUIRE_CORPUS();
    for (const std::string& piece : kCratePieces) {
        const fs::path file = kChess / "assets" / piece / (piece + "_geom.usd");
        ASSERT_TRUE(bytesOf(file).starts_with("PXR-USDC")) << file;
        auto stage = openFile(file.string());
        ASSERT_TRUE(stage) << file;
        EXPECT_EQ(stage->metadata().metersPerUnit, 1.0);
        EXPECT_EQ(stage->metadata().upAxis, "Y");
        EXPECT_EQ(stage->metadata().defaultPrim, piece);
        size_t meshes = 0;
        expectValidMeshes(*stage, &meshes, piece != "Pawn");
        EXPECT_EQ(meshes, piece == "Pawn" ? 2u : 1u) << file;
    }
}

// The Knight's geometry was written as text by the same exporter: a binary piece must have the same
// prims, attribute names and declared types.
TEST(CrateCorpus, BinaryPieceHasTheSchemaOfTheTextPiece) {
    REQUIRE_CORPUS();
    auto text = openFile((kChess / "assets/Knight/Knight_geom.usd").string());
    auto binary = openFile((kChess / "assets/Rook/Rook_geom.usd").string());
    ASSERT_TRUE(text && binary);
    const Prim* textMesh = text->find("/Knight/Geom/Render");
    const Prim* binaryMesh = binary->find("/Rook/Geom/Render");
    ASSERT_TRUE(textMesh && binaryMesh);
    EXPECT_EQ(textMesh->typeName, binaryMesh->typeName);
    EXPECT_EQ(binary->find("/Rook/Geom")->typeName, text->find("/Knight/Geom")->typeName);
    EXPECT_EQ(binary->find("/Rook")->kind, text->find("/Knight")->kind);
    std::map<std::string, std::string> textTypes, binaryTypes;
    for (const auto& [name, attr] : textMesh->attributes) textTypes[name] = attr.typeName;
    for (const auto& [name, attr] : binaryMesh->attributes) binaryTypes[name] = attr.typeName;
    EXPECT_EQ(textTypes, binaryTypes);
    EXPECT_EQ(textMesh->attribute("points")->metadata.at("interpolation").strings,
              binaryMesh->attribute("points")->metadata.at("interpolation").strings);
    // "int[] primvars:st:indices = None" in text: a blocked default in both.
    EXPECT_FALSE(textMesh->attribute("primvars:st:indices")->defaultValue);
    EXPECT_FALSE(binaryMesh->attribute("primvars:st:indices")->defaultValue);
}

// The assembly: text layers with class inherits, payloads and variants over binary geometry.
TEST(CrateCorpus, ChessSetComposesAcrossTextAndBinaryLayers) {
    REQUIRE_CORPUS();
    auto stage = openFile((kChess / "chess_set.usda").string());
    ASSERT_TRUE(stage);
    size_t meshes = 0;
    expectValidMeshes(*stage, &meshes);
    // Each reference in the assembly brings one mesh, except the two Pawn prototypes of the point
    // instancers, which bring the Pawn's two.
    const std::string assembly = bytesOf(kChess / "chess_set.usda");
    size_t references = 0;
    for (size_t at = assembly.find("add references"); at != std::string::npos; at = assembly.find("add references", at + 1))
        ++references;
    EXPECT_EQ(references, 19u);
    EXPECT_EQ(meshes, (references - 2) + 2 * 2);
    // The looks bind materials that the pieces' MaterialX documents define.
    size_t bound = 0;
    for (const Prim* prim : stage->prims())
        if (const Relationship* binding = prim->relationship("material:binding")) {
            const Prim* material = binding->targets.empty() ? nullptr : stage->find(binding->targets.front());
            EXPECT_TRUE(material && material->typeName == "Material") << prim->path;
            ++bound;
        }
    EXPECT_EQ(bound, meshes);
    for (const Warning& warning : stage->warnings())
        EXPECT_EQ(warning.message.find("MaterialX"), std::string::npos) << warning.message;
}

// ---- Errors ---------------------------------------------------------------------------------------

std::string rookBytes() { return bytesOf(kChess / "assets/Rook/Rook_geom.usd"); }

std::string crateError(const std::string& bytes) {
    const Error error = openError(bytes, "bad.usdc");
    return error.str();
}

TEST(CrateErrors, TruncatedFileNamesTheTableOfContents) {
    REQUIRE_CORPUS();
    const std::string message = crateError(rookBytes().substr(0, 4096));
    EXPECT_EQ(message.rfind("bad.usdc: byte 16: table of contents at byte ", 0), 0u) << message;
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    EXPECT_EQ(crateError(rookBytes().substr(0, 40)), "bad.usdc: byte 0: file of 40 bytes is too short for the crate header");
}

TEST(CrateErrors, UnknownVersionIsNamed) {
    REQUIRE_CORPUS();
    std::string bytes = rookBytes();
    bytes[9] = 42;  // minor version
    EXPECT_EQ(crateError(bytes), "bad.usdc: byte 8: crate version 0.42.0 is not supported (reads 0.4.0 to 0.12.0)");
    bytes[9] = 3;
    EXPECT_NE(crateError(bytes).find("crate version 0.3.0 is not supported"), std::string::npos);
}

TEST(CrateErrors, BadOffsetsAreNamed) {
    REQUIRE_CORPUS();
    std::string bytes = rookBytes();
    uint64_t toc = 0;
    std::memcpy(&toc, bytes.data() + 16, 8);
    // The first section's start pushed past the end of the file.
    std::string badSection = bytes;
    const uint64_t far = bytes.size() * 2;
    std::memcpy(badSection.data() + toc + 8 + 16, &far, 8);
    const std::string message = crateError(badSection);
    EXPECT_EQ(message.rfind("bad.usdc: byte " + std::to_string(toc + 8) + ": section ", 0), 0u) << message;
    EXPECT_NE(message.find("lies outside the file"), std::string::npos) << message;
    // A section's start moved into other data: its contents are checked, not trusted.
    std::string shifted = bytes;
    uint64_t start = 0;
    std::memcpy(&start, bytes.data() + toc + 8 + 16, 8);
    start += 5;
    std::memcpy(shifted.data() + toc + 8 + 16, &start, 8);
    EXPECT_NE(crateError(shifted).find("bad.usdc: byte "), std::string::npos);
}

// Corrupted bytes anywhere: a clear error or a stage, never a crash (run under the sanitizers by the
// fuzz build too).
TEST(CrateErrors, CorruptBytesNeverCrash) {
    REQUIRE_CORPUS();
    std::string problem;
    auto package = assets::UsdzPackage::open(bytesOf(kRigged), &problem);
    ASSERT_TRUE(package) << problem;
    const std::string original = *package->read(package->rootLayer(), &problem);
    uint64_t state = 12345;
    auto next = [&] { return (state = state * 6364136223846793005ull + 1442695040888963407ull) >> 33; };
    for (int trial = 0; trial < 300; ++trial) {
        std::string bytes = original;
        const int flips = 1 + static_cast<int>(next() % 8);
        for (int f = 0; f < flips; ++f) bytes[next() % bytes.size()] = static_cast<char>(next());
        auto result = Stage::openFromString(bytes, "fuzz.usdc");
        if (const Error* error = std::get_if<Error>(&result)) {
            EXPECT_FALSE(error->message.empty());
        }
    }
}

// ---- USDZ packages --------------------------------------------------------------------------------

void expectSameValue(const std::optional<Value>& a, const std::optional<Value>& b, const std::string& what) {
    ASSERT_EQ(a.has_value(), b.has_value()) << what;
    if (!a) return;
    EXPECT_EQ(a->typeName, b->typeName) << what;
    EXPECT_EQ(a->numbers, b->numbers) << what;
    EXPECT_EQ(a->strings, b->strings) << what;
}

// The package holds the text scene beside it (with its own line endings): the composed stages
// match prim by prim, attribute by attribute.
TEST(Package, ComposesLikeTheSceneItPackages) {
    REQUIRE_CORPUS();
    auto loose = openFile((kNormals / "NormalsTextureBiasAndScale.usda").string());
    auto packaged = openFile((kNormals / "NormalsTextureBiasAndScale.usdz").string());
    ASSERT_TRUE(loose && packaged);
    const auto a = loose->prims();
    const auto b = packaged->prims();
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i]->path, b[i]->path);
        EXPECT_EQ(a[i]->typeName, b[i]->typeName) << a[i]->path;
        ASSERT_EQ(a[i]->attributes.size(), b[i]->attributes.size()) << a[i]->path;
        for (const auto& [name, attr] : a[i]->attributes) {
            const Attribute* other = b[i]->attribute(name);
            ASSERT_TRUE(other) << a[i]->path << "." << name;
            EXPECT_EQ(attr.typeName, other->typeName);
            expectSameValue(attr.defaultValue, other->defaultValue, a[i]->path + "." + name);
            EXPECT_EQ(attr.connection, other->connection);
        }
    }
    // Layers inside the package are named by package paths.
    EXPECT_EQ(b.front()->where.file, (kNormals / "NormalsTextureBiasAndScale.usdz").string() + "[NormalsTextureBiasAndScale.usda]");
}

TEST(Package, BinaryLayerWithSkinningAndAnimationComposes) {
    REQUIRE_CORPUS();
    auto stage = openFile(kRigged.string());
    ASSERT_TRUE(stage);
    size_t meshes = 0;
    expectValidMeshes(*stage, &meshes);
    EXPECT_EQ(meshes, 1u);
    const Prim* animation = stage->find("/RiggedSimple/Animations/skelAnim_0");
    ASSERT_TRUE(animation);
    const Attribute* rotations = animation->attribute("rotations");
    ASSERT_TRUE(rotations);
    EXPECT_GT(rotations->timeSamples.size(), 1u);
    // Joint rotations are unit quaternions, the real part first (as .usda writes them).
    for (const auto& [time, value] : rotations->timeSamples) {
        ASSERT_EQ(value.tupleSize, 4);
        for (size_t q = 0; q + 3 < value.numbers.size(); q += 4) {
            const double norm = std::hypot(value.numbers[q], value.numbers[q + 1], value.numbers[q + 2]);
            EXPECT_NEAR(std::hypot(norm, value.numbers[q + 3]), 1.0, 1e-6) << time;
        }
    }
    EXPECT_EQ(animation->attribute("scales")->timeSamples.begin()->second.typeName, "half3");
}

TEST(Package, ArcsIntoAPackageByItsPathOrAnEntry) {
    REQUIRE_CORPUS();
    const std::string archive = fs::absolute(kRigged).string();
    auto stage = open("#usda 1.0\n"
                      "def \"Whole\" (references = @" + archive + "@</RiggedSimple>) {}\n"
                      "def \"Entry\" (references = @" + archive + "[RiggedSimple.imported.usdc]@</RiggedSimple>) {}\n");
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->find("/Whole/Geom/Z_UP/Armature/Bone_3/Cylinder_2"));
    EXPECT_TRUE(stage->find("/Entry/Geom/Z_UP/Armature/Bone_3/Cylinder_2"));
    // An entry the package does not hold: the arc is reported and adds nothing (missing_layers_test.cpp).
    auto missing = open("#usda 1.0\ndef \"X\" (references = @" + archive + "[nothing.usda]@) {}\n");
    ASSERT_TRUE(missing && missing->find("/X"));
    ASSERT_EQ(missing->warnings().size(), 1u);
    const std::string why = fs::path(archive).lexically_normal().string() + ": no file 'nothing.usda' in the package";
    EXPECT_NE(missing->warnings()[0].message.find(why), std::string::npos) << missing->warnings()[0].message;
}

// Files in a package are read from the archive in memory, as the plugin reads textures: the
// packaged normal map is the one shipped beside the package.
TEST(Package, PackagedFilesAreReadFromTheArchive) {
    REQUIRE_CORPUS();
    const std::string archive = (kNormals / "NormalsTextureBiasAndScale.usdz").string();
    assets::AssetReader assets;
    std::string problem;
    const auto bytes = assets.read(assets::joinPackagePath(archive, "r_normal_map.png"), &problem);
    ASSERT_TRUE(bytes) << problem;
    EXPECT_EQ(*bytes, bytesOf(kNormals / "r_normal_map.png"));
    EXPECT_FALSE(assets.read(assets::joinPackagePath(archive, "missing.png"), &problem));
    EXPECT_EQ(problem, "no file 'missing.png' in the package");
}

// A package inside a package (written here): its layers compose, arcs into it by a nested package
// path and relative to a layer in the outer package alike.
TEST(Package, LayersOfAPackageInsideAPackageCompose) {
    using obscura::test::fileBytes;
    using obscura::test::writeUsdz;
    const fs::path dir = fs::temp_directory_path() / ("obscura_nested_package_" + std::to_string(::getpid()));
    const std::string inner = "#usda 1.0\ndef \"Inside\" {\n    def \"Child\" {}\n}\n";
    const std::string scene = "#usda 1.0\ndef \"Relative\" (references = @inner.usdz[inner.usda]@</Inside>) {}\n";
    ASSERT_EQ(writeUsdz(dir / "inner.usdz", {{"inner.usda", inner}}), "");
    ASSERT_EQ(writeUsdz(dir / "outer.usdz", {{"scene.usda", scene}, {"inner.usdz", fileBytes(dir / "inner.usdz")}}),
              "");
    fs::remove(dir / "inner.usdz");
    auto packaged = openFile((dir / "outer.usdz").string());
    const std::string nested = (dir / "outer.usdz").string() + "[inner.usdz[inner.usda]]";
    auto referencing = open("#usda 1.0\ndef \"Absolute\" (references = @" + nested + "@</Inside>) {}\n");
    fs::remove_all(dir);
    ASSERT_TRUE(packaged && referencing);
    EXPECT_TRUE(packaged->find("/Relative/Child"));
    EXPECT_TRUE(referencing->find("/Absolute/Child"));
}

TEST(Package, AMissingMaterialXDocumentWarnsAndAddsNothing) {
    auto stage = open("#usda 1.0\ndef \"M\" (references = @looks.mtlx@)\n{\n    def \"Child\" {\n    }\n}\n");
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->find("/M/Child"));
    ASSERT_FALSE(stage->warnings().empty());
    EXPECT_EQ(stage->warnings().front().message, "reference of </M> to @looks.mtlx@ ignored: looks.mtlx: no such file");
    EXPECT_EQ(stage->warnings().front().where.line, 2);
}

}  // namespace
}  // namespace obscura::usda::test
