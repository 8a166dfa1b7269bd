// Textures in USDZ packages through the harness's scene host and the plugin, which reads them from
// the archive in memory: the host hands on package paths ("/dir/a.usdz[tex/b.png]") and no file
// is written anywhere (each test runs with TMPDIR in a fresh folder that must stay empty). Single
// textures (PNG and OpenEXR, relative to a layer in the package, named a.usdz[...] from a layer on
// disk, in a package inside a package) and UDIM sets (a <UDIM> pattern, four solid-colour tiles)
// on a plane whose view shows one colour per quarter. The packages are zip archives written here
// with libzip, entries stored.
#include "harness/image/exr_writer.h"
#include "harness/image/png_io.h"
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"
#include "tests/support/usdz_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

namespace obscura::test {
namespace {

namespace fs = std::filesystem;

using Rgb8 = std::array<uint8_t, 3>;
// The colour of each quarter of the view, by the UDIM tile whose square it shows.
const std::map<int, Rgb8> kTiles = {
    {1001, {200, 40, 40}}, {1002, {40, 200, 40}}, {1011, {40, 40, 200}}, {1012, {220, 220, 60}}};

// The camera's view filled by a plane with st from (0, 0) to (extent, extent), its material reading
// raw texels of `file` for diffuseColor (unauthored, 0.18, where the texture cannot be read).
std::string planeScene(const std::string& file, int extent) {
    const std::string st = std::to_string(extent);
    return R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Y"
)
)" + usdaCamera() + R"(def Mesh "Plane"
{
    point3f[] points = [(-1.04775, -1.04775, 0), (1.04775, -1.04775, 0), (1.04775, 1.04775, 0), (-1.04775, 1.04775, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    uniform token subdivisionScheme = "none"
    texCoord2f[] primvars:st = [(0, 0), ()" + st + ", 0), (" + st + ", " + st + "), (0, " + st + R"()] (
        interpolation = "vertex"
    )
    rel material:binding = </M>
}
def Material "M"
{
    token outputs:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:diffuseColor.connect = </M/Texture.outputs:rgb>
        token outputs:surface
    }
    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @)" + file + R"(@
        token inputs:sourceColorSpace = "raw"
        float2 inputs:st.connect = </M/Reader.outputs:result>
        float3 outputs:rgb
    }
    def Shader "Reader"
    {
        uniform token info:id = "UsdPrimvarReader_float2"
        token inputs:varname = "st"
        float2 outputs:result
    }
}
)";
}

// An 8 x 8 image, each 4 x 4 quarter the colour of the tile whose square it would cover (row 0 is
// the top, t = 1), as codes / 255.
std::vector<float> quartersTexels() {
    std::vector<float> texels;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (uint8_t code : kTiles.at(1001 + x / 4 + 10 * (1 - y / 4))) texels.push_back(code / 255.0f);
    return texels;
}

std::vector<uint8_t> codes(const std::vector<float>& texels) {
    std::vector<uint8_t> out;
    for (float t : texels) out.push_back(uint8_t(std::lround(t * 255.0f)));
    return out;
}

std::vector<float> solidTexels(Rgb8 colour) {
    std::vector<float> texels;
    for (int i = 0; i < 64; ++i)
        for (uint8_t code : colour) texels.push_back(code / 255.0f);
    return texels;
}

class UsdzTextureTest : public ::testing::Test {
protected:
    UsdzTextureTest() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("obscura_usdz_texture_" + std::string(info->name()) + "_" + std::to_string(getpid()));
        fs::create_directories(dir_ / "tmp");
        for (const auto& [number, colour] : kTiles)
            tiles_["tex/body." + std::to_string(number) + ".png"] = png(solidTexels(colour));
        // What the process writes to temporary files goes here, which stays empty.
        if (const char* tmp = std::getenv("TMPDIR")) previousTmp_ = tmp;
        ::setenv("TMPDIR", (dir_ / "tmp").c_str(), 1);
    }
    ~UsdzTextureTest() override {
        if (previousTmp_) ::setenv("TMPDIR", previousTmp_->c_str(), 1);
        else ::unsetenv("TMPDIR");
        fs::remove_all(dir_);
    }

    // An 8 x 8 RGB PNG's bytes.
    std::string png(const std::vector<float>& texels) const {
        const fs::path file = dir_ / "scratch.png";
        const std::vector<uint8_t> rgb = codes(texels);
        auto written = image::writePng(file.string(), 8, 8, image::PngFormat::Rgb, rgb.data(), 8 * 3);
        EXPECT_FALSE(image::isError(written)) << image::errorOf(written);
        return fileBytes(file);
    }
    // An 8 x 8 half-float RGBA OpenEXR file's bytes.
    std::string exr(const std::vector<float>& rgbTexels) const {
        std::vector<float> rgba;
        for (size_t i = 0; i < rgbTexels.size(); i += 3)
            rgba.insert(rgba.end(), {rgbTexels[i], rgbTexels[i + 1], rgbTexels[i + 2], 1.0f});
        const fs::path file = dir_ / "scratch.exr";
        image::ExrLayer layer{
            "", {"R", "G", "B", "A"}, image::ExrLayer::PixelType::Half, rgba.data(), 8 * 4 * sizeof(float)};
        EXPECT_FALSE(image::isError(image::writeExr(file.string(), 8, 8, {layer})));
        return fileBytes(file);
    }
    void writePackage(const fs::path& archive, const PackageFiles& files) { ASSERT_EQ(writeUsdz(archive, files), ""); }
    // The tiles and, beside them, files of no set (not a tile number, another name).
    PackageFiles tileEntries() const {
        PackageFiles entries(tiles_.begin(), tiles_.end());
        entries.emplace_back("tex/body.0999.png", tiles_.begin()->second);
        entries.emplace_back("tex/other.png", tiles_.begin()->second);
        return entries;
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    void expectNothingWritten() const {
        EXPECT_TRUE(fs::is_empty(dir_ / "tmp")) << fs::directory_iterator(dir_ / "tmp")->path();
    }

    fs::path dir_;
    std::map<std::string, std::string> tiles_;  // package name -> PNG bytes

private:
    std::optional<std::string> previousTmp_;
};
using UdimUsdzTest = UsdzTextureTest;

std::vector<float> render(HostedStage& scene) {
    scene.setBool("textures:compression", false);  // the texels' exact codes
    scene.setBool("taa", false);                   // each pixel shows its centre
    return scene.renderAlbedo();
}

// Each quarter of the view shows its tile's colour: st (s, t) in [0, 2)^2 lies in tile 1001 +
// floor(s) + 10 floor(t), and t grows upwards.
void expectQuarters(const std::vector<float>& albedo, const char* what) {
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3) << what;
    for (const auto& [number, colour] : kTiles) {
        const int u = (number - 1001) % 10, v = (number - 1001) / 10;
        const int x = kWidth / 4 + u * kWidth / 2, y = kHeight / 4 + (1 - v) * kHeight / 2;
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(albedo[(size_t(y) * kWidth + size_t(x)) * 3 + c], colour[c] / 255.0f, 0.01f)
                << what << ": tile " << number << " channel " << c;
    }
}

void expectClean(const HostedStage& scene) {
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
}

// diffuseColor's constant (unauthored: 0.18) at pixel (x, y), where the texture could not be read.
void expectTheConstantAt(const std::vector<float>& albedo, int x, int y) {
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    for (size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(albedo[(size_t(y) * kWidth + size_t(x)) * 3 + c], 0.18f, 0.01f) << "channel " << c;
}

// The one thing said: a warning naming the material and where the texture was looked for.
void expectOneWarning(const HostedStage& scene, const std::string& where) {
    std::vector<std::string> all = scene.warnings;
    for (const auto& m : scene.host->messages()) all.push_back(m.text);
    ASSERT_EQ(all.size(), 1u) << (all.empty() ? "no warning" : all.back());
    EXPECT_NE(all.front().find("/M"), std::string::npos) << all.front();
    EXPECT_NE(all.front().find(where), std::string::npos) << all.front();
}

TEST_F(UsdzTextureTest, ATextureInThePackageIsReadFromTheArchive) {
    writePackage(dir_ / "scene.usdz", {{"scene.usda", planeScene("tex/quarters.png", 1)},
                                       {"tex/quarters.png", png(quartersTexels())}});
    HostedStage scene(usda::Stage::open(dir_ / "scene.usdz"));
    expectQuarters(render(scene), "texture in the package");
    expectClean(scene);
    EXPECT_EQ(scene.token("/M", "obscura:diffuseColor:file"), path("scene.usdz") + "[tex/quarters.png]");
    expectNothingWritten();
}

TEST_F(UsdzTextureTest, APackagePathWrittenInALayerOnDiskReadsTheFileInIt) {
    writePackage(dir_ / "textures.usdz", {{"tex/quarters.png", png(quartersTexels())}});
    std::ofstream(dir_ / "scene.usda") << planeScene("textures.usdz[tex/quarters.png]", 1);
    HostedStage scene(usda::Stage::open(dir_ / "scene.usda"));
    expectQuarters(render(scene), "package path");
    expectClean(scene);
    EXPECT_EQ(scene.token("/M", "obscura:diffuseColor:file"), path("textures.usdz") + "[tex/quarters.png]");
    expectNothingWritten();
}

TEST_F(UsdzTextureTest, APackageInsideThePackageIsReadToo) {
    writePackage(dir_ / "inner.usdz", {{"tex/quarters.png", png(quartersTexels())}});
    writePackage(dir_ / "outer.usdz", {{"scene.usda", planeScene("inner.usdz[tex/quarters.png]", 1)},
                                       {"inner.usdz", fileBytes(dir_ / "inner.usdz")}});
    fs::remove(dir_ / "inner.usdz");
    HostedStage scene(usda::Stage::open(dir_ / "outer.usdz"));
    expectQuarters(render(scene), "package inside the package");
    expectClean(scene);
    EXPECT_EQ(scene.token("/M", "obscura:diffuseColor:file"), path("outer.usdz") + "[inner.usdz[tex/quarters.png]]");
    expectNothingWritten();
}

TEST_F(UsdzTextureTest, AnOpenExrTextureInThePackageIsReadFromTheArchive) {
    writePackage(dir_ / "scene.usdz", {{"scene.usda", planeScene("quarters.exr", 1)},
                                       {"quarters.exr", exr(quartersTexels())}});
    HostedStage scene(usda::Stage::open(dir_ / "scene.usdz"));
    expectQuarters(render(scene), "OpenEXR texture");
    expectClean(scene);
    expectNothingWritten();
}

TEST_F(UsdzTextureTest, AFileMissingFromThePackageWarnsOnceAndKeepsTheConstant) {
    writePackage(dir_ / "scene.usdz", {{"scene.usda", planeScene("tex/none.png", 1)},
                                       {"tex/quarters.png", png(quartersTexels())}});
    HostedStage scene(usda::Stage::open(dir_ / "scene.usdz"));
    expectTheConstantAt(render(scene), kWidth / 2, kHeight / 2);
    expectOneWarning(scene, path("scene.usdz") + "[tex/none.png]");
    expectNothingWritten();
}

TEST_F(UsdzTextureTest, AnUnreadablePackageWarnsOnceAndKeepsTheConstant) {
    std::ofstream(dir_ / "broken.usdz") << "not a zip archive";
    std::ofstream(dir_ / "scene.usda") << planeScene("broken.usdz[tex/quarters.png]", 1);
    HostedStage scene(usda::Stage::open(dir_ / "scene.usda"));
    expectTheConstantAt(render(scene), kWidth / 2, kHeight / 2);
    expectOneWarning(scene, path("broken.usdz") + "[tex/quarters.png]");
    expectNothingWritten();
}

TEST_F(UdimUsdzTest, APatternRelativeToALayerOnDiskReadsEachTile) {
    for (const auto& [name, bytes] : tiles_) {
        fs::create_directories((dir_ / "disk" / name).parent_path());
        std::ofstream(dir_ / "disk" / name, std::ios::binary) << bytes;
    }
    std::ofstream(dir_ / "disk/scene.usda") << planeScene("tex/body.<UDIM>.png", 2);
    HostedStage scene(usda::Stage::open(dir_ / "disk/scene.usda"));
    expectQuarters(render(scene), "layer on disk");
    expectClean(scene);
}

TEST_F(UdimUsdzTest, APatternRelativeToALayerInAPackageReadsTheTilesInIt) {
    auto entries = tileEntries();
    entries.insert(entries.begin(), {"scene.usda", planeScene("tex/body.<UDIM>.png", 2)});  // the root layer first
    writePackage(dir_ / "package/scene.usdz", entries);
    HostedStage scene(usda::Stage::open(dir_ / "package/scene.usdz"));
    expectQuarters(render(scene), "layer in a package");
    expectClean(scene);
    // The plugin was handed the set in the package, whose tiles it found among the package's files.
    EXPECT_EQ(scene.token("/M", "obscura:diffuseColor:file"), path("package/scene.usdz") + "[tex/body.<UDIM>.png]");
    expectNothingWritten();
}

TEST_F(UdimUsdzTest, APatternNamingAPackagesFileReadsTheTilesInIt) {
    writePackage(dir_ / "tiles.usdz", tileEntries());
    std::ofstream(dir_ / "scene.usda") << planeScene("tiles.usdz[tex/body.<UDIM>.png]", 2);
    HostedStage scene(usda::Stage::open(dir_ / "scene.usda"));
    expectQuarters(render(scene), "package path");
    expectClean(scene);
    expectNothingWritten();
}

TEST_F(UdimUsdzTest, APatternWithNoTileInThePackageWarnsOnceAndTheRestRenders) {
    std::string text = planeScene("tex/none.<UDIM>.png", 2);
    // A second plane in front of the right half, in a colour of its own.
    text += R"(def Mesh "Right"
{
    point3f[] points = [(0, -1.04775, 0.5), (1.04775, -1.04775, 0.5), (1.04775, 1.04775, 0.5), (0, 1.04775, 0.5)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    uniform token subdivisionScheme = "none"
    color3f[] primvars:displayColor = [(0.25, 0.5, 0.75)]
}
)";
    auto entries = tileEntries();
    entries.insert(entries.begin(), {"scene.usda", text});
    writePackage(dir_ / "scene.usdz", entries);
    HostedStage scene(usda::Stage::open(dir_ / "scene.usdz"));
    const std::vector<float> albedo = render(scene);
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    const size_t right = (size_t(kHeight / 2) * kWidth + size_t(3 * kWidth / 4)) * 3;
    EXPECT_NEAR(albedo[right + 0], 0.25f, 0.01f);
    EXPECT_NEAR(albedo[right + 1], 0.5f, 0.01f);
    EXPECT_NEAR(albedo[right + 2], 0.75f, 0.01f);
    expectTheConstantAt(albedo, kWidth / 4, kHeight / 2);
    expectOneWarning(scene, path("scene.usdz") + "[tex/none.<UDIM>.png]");
    expectNothingWritten();
}

}  // namespace
}  // namespace obscura::test
