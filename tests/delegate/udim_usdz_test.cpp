// UDIM texture sets through the harness's scene host and the plugin, from a layer on disk and from
// USDZ packages: a UsdUVTexture whose file is a <UDIM> pattern, four solid-colour tiles written
// here as PNGs, and a plane whose st spans two by two tile squares, each quarter of the view
// showing its tile. The packages are written here (tests/support/usdz_writer.h).
#include "harness/image/png_io.h"
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"
#include "tests/support/usdz_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace obscura::test {
namespace {

namespace fs = std::filesystem;

using Rgb8 = std::array<uint8_t, 3>;
const std::map<int, Rgb8> kTiles = {
    {1001, {200, 40, 40}}, {1002, {40, 200, 40}}, {1011, {40, 40, 200}}, {1012, {220, 220, 60}}};

// The camera's view filled by a plane with st from (0, 0) to (2, 2), its material reading raw
// texels of `file`; a second material, bound to nothing textured, keeps its constant.
std::string planeScene(const std::string& file) {
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
    texCoord2f[] primvars:st = [(0, 0), (2, 0), (2, 2), (0, 2)] (
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

// A solid 8 x 8 RGB PNG's bytes.
std::string tilePng(const fs::path& scratch, Rgb8 colour) {
    std::vector<uint8_t> texels;
    for (int i = 0; i < 64; ++i) texels.insert(texels.end(), colour.begin(), colour.end());
    const fs::path file = scratch / "tile.png";
    auto written = image::writePng(file.string(), 8, 8, image::PngFormat::Rgb, texels.data(), 8 * 3);
    EXPECT_FALSE(image::isError(written)) << image::errorOf(written);
    std::ifstream in(file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

class UdimUsdzTest : public ::testing::Test {
protected:
    UdimUsdzTest() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("obscura_udim_usdz_" + std::string(info->name()) + "_" + std::to_string(getpid()));
        fs::create_directories(dir_);
        for (const auto& [number, colour] : kTiles)
            tiles_["tex/body." + std::to_string(number) + ".png"] = tilePng(dir_, colour);
    }
    ~UdimUsdzTest() override { fs::remove_all(dir_); }

    // The tiles and, beside them, files of no set (not a tile number, another name).
    PackageEntries tileEntries() const {
        PackageEntries entries(tiles_.begin(), tiles_.end());
        entries.emplace_back("tex/body.0999.png", tiles_.begin()->second);
        entries.emplace_back("tex/other.png", tiles_.begin()->second);
        return entries;
    }

    fs::path dir_;
    std::map<std::string, std::string> tiles_;  // package name -> PNG bytes
};

std::vector<float> render(HostedStage& scene) {
    scene.setBool("textures:compression", false);  // the tiles' exact codes
    scene.setBool("taa", false);                   // each pixel shows its centre
    return scene.renderAlbedo();
}

// Each quarter of the view shows its tile: st (s, t) in [0, 2)^2 lies in tile 1001 + floor(s) +
// 10 floor(t), and t grows upwards.
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

TEST_F(UdimUsdzTest, APatternRelativeToALayerOnDiskReadsEachTile) {
    for (const auto& [name, bytes] : tiles_) {
        fs::create_directories((dir_ / "disk" / name).parent_path());
        std::ofstream(dir_ / "disk" / name, std::ios::binary) << bytes;
    }
    std::ofstream(dir_ / "disk/scene.usda") << planeScene("tex/body.<UDIM>.png");
    HostedStage scene(usda::Stage::open(dir_ / "disk/scene.usda"));
    expectQuarters(render(scene), "layer on disk");
    expectClean(scene);
}

TEST_F(UdimUsdzTest, APatternRelativeToALayerInAPackageReadsTheTilesInIt) {
    auto entries = tileEntries();
    entries.insert(entries.begin(), {"scene.usda", planeScene("tex/body.<UDIM>.png")});  // the root layer comes first
    ASSERT_EQ(writePackage(dir_ / "package/scene.usdz", entries), "");
    HostedStage scene(usda::Stage::open(dir_ / "package/scene.usdz"));
    expectQuarters(render(scene), "layer in a package");
    expectClean(scene);
    // Only the set's tiles were extracted, side by side.
    const fs::path pattern = scene.token("/M", "obscura:diffuseColor:file");
    EXPECT_EQ(pattern.filename(), "body.<UDIM>.png");
    std::vector<std::string> extracted;
    for (const auto& entry : fs::directory_iterator(pattern.parent_path()))
        extracted.push_back(entry.path().filename());
    std::sort(extracted.begin(), extracted.end());
    EXPECT_EQ(extracted,
              (std::vector<std::string>{"body.1001.png", "body.1002.png", "body.1011.png", "body.1012.png"}));
}

TEST_F(UdimUsdzTest, APatternNamingAPackagesEntryReadsTheTilesInIt) {
    ASSERT_EQ(writePackage(dir_ / "tiles.usdz", tileEntries()), "");
    std::ofstream(dir_ / "scene.usda") << planeScene("tiles.usdz[tex/body.<UDIM>.png]");
    HostedStage scene(usda::Stage::open(dir_ / "scene.usda"));
    expectQuarters(render(scene), "package entry");
    expectClean(scene);
}

TEST_F(UdimUsdzTest, APatternWithNoTileInThePackageWarnsOnceAndTheRestRenders) {
    std::string text = planeScene("tex/none.<UDIM>.png");
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
    ASSERT_EQ(writePackage(dir_ / "scene.usdz", entries), "");
    HostedStage scene(usda::Stage::open(dir_ / "scene.usdz"));
    const std::vector<float> albedo = render(scene);
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    const size_t right = (size_t(kHeight / 2) * kWidth + size_t(3 * kWidth / 4)) * 3;
    EXPECT_NEAR(albedo[right + 0], 0.25f, 0.01f);
    EXPECT_NEAR(albedo[right + 1], 0.5f, 0.01f);
    EXPECT_NEAR(albedo[right + 2], 0.75f, 0.01f);
    // One warning, naming the material and where the set was looked for.
    const std::string where = (dir_ / "scene.usdz").string() + "[tex/none.<UDIM>.png]";
    std::vector<std::string> all = scene.warnings;
    for (const auto& m : scene.host->messages()) all.push_back(m.text);
    ASSERT_EQ(all.size(), 1u) << all.front();
    EXPECT_NE(all.front().find("/M"), std::string::npos) << all.front();
    EXPECT_NE(all.front().find(where), std::string::npos) << all.front();
}

}  // namespace
}  // namespace obscura::test
