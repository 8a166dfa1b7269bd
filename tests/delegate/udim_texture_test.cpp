// UDIM texture sets end to end through the ABI: solid-colour tiles written here as PNGs, named by
// a <UDIM> pattern on obscura:diffuseColor:file, looked up with a plane's primvars:st spanning
// three by two tile squares, read back from the albedo AOV. The camera sees exactly the plane, so
// pixel (x, y) shows st (3 (x + 0.5) / 64, 2 (1 - (y + 0.5) / 64)).
#include "harness/image/png_io.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

namespace obscura::test {
namespace {

constexpr double kDistance = 5.0;
constexpr float kFocalLength = 50.0f, kAperture = 20.955f;
const float kHalf = float(kAperture / 2.0 / kFocalLength * kDistance);  // the plane fills the view
constexpr double kColumns = 3.0, kRows = 2.0;                        // the st squares the plane spans

using Rgb8 = std::array<uint8_t, 3>;
// Tile colours by tile number; 1012 (top row, middle) has no file.
const std::map<int, Rgb8> kTiles = {
    {1001, {200, 40, 40}}, {1002, {40, 200, 40}}, {1003, {40, 40, 200}}, {1011, {220, 220, 60}}, {1013, {200, 60, 200}}};
constexpr int kMissingTile = 1012;

class UdimTextureTest : public ::testing::Test {
protected:
    UdimTextureTest() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("obscura_udim_" + std::string(info->name()) + "_" + std::to_string(getpid()));
        std::filesystem::create_directories(dir_);
        host.addCamera("/Camera", translation(0, 0, kDistance), kFocalLength, kAperture);
        host.addRenderBuffer("/Buffers/albedo", "float32Vec3", kWidth, kHeight);
        // One sample per pixel at its centre: a pixel by a seam shows what the texture holds there,
        // not what temporal AA's jitter would average across the seam.
        setBool(host, "taa", false);
    }
    ~UdimTextureTest() override { std::filesystem::remove_all(dir_); }

    void setCompression(bool on) {
        int32_t flag = on ? 1 : 0;
        ObscuraValue v{OBSCURA_VALUE_BOOL, 0, 1, &flag};
        ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "textures:compression", &v), OBSCURA_OK);
    }

    // A solid `size` x `size` RGB PNG.
    void writeTile(const std::string& name, int size, Rgb8 colour) {
        std::vector<uint8_t> bytes;
        for (int i = 0; i < size * size; ++i) bytes.insert(bytes.end(), colour.begin(), colour.end());
        auto written = image::writePng((dir_ / name).string(), size, size, image::PngFormat::Rgb, bytes.data(),
                                       size_t(size) * 3);
        ASSERT_FALSE(image::isError(written)) << image::errorOf(written);
    }
    // The set's tiles, 1002 larger than the others (resampled to one square size), and its pattern.
    std::string writeTiles() {
        for (const auto& [number, colour] : kTiles)
            writeTile("body." + std::to_string(number) + ".png", number == 1002 ? 32 : 16, colour);
        return (dir_ / "body.<UDIM>.png").string();
    }

    void addPlane(const std::string& file, std::array<float, 3> constant = {0.5f, 0.5f, 0.5f}) {
        host.addPrim("material", "/Looks/M",
                     {{"obscura:diffuseColor:file", HostValue::token(file)},
                      {"inputs:diffuseColor", HostValue::float3(constant[0], constant[1], constant[2])}});
        const float s = float(kColumns), t = float(kRows);
        host.addPrim("mesh", "/Plane",
                     {{"points", HostValue::points({{-kHalf, -kHalf, 0}, {kHalf, -kHalf, 0}, {kHalf, kHalf, 0},
                                                    {-kHalf, kHalf, 0}})},
                      {"faceVertexCounts", HostValue::intArray({4})},
                      {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                      {"subdivisionScheme", HostValue::token("none")},
                      {"primvars:st", HostValue::float2Array({{0, 0}, {s, 0}, {s, t}, {0, t}})},
                      {"material:binding", HostValue::path("/Looks/M")}});
    }

    void render() {
        ASSERT_EQ(host.render("/Camera", {{"albedo", "/Buffers/albedo"}}), OBSCURA_OK) << host.lastError();
        ASSERT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
        albedo = host.readFloats("/Buffers/albedo");
    }
    std::array<float, 3> albedoAt(int x, int y) const {
        const float* p = &albedo[(size_t(y) * kWidth + size_t(x)) * 3];
        return {p[0], p[1], p[2]};
    }
    void expectEachSquareShowsItsTile(float tolerance) const;
    bool warned(const std::string& text) const {
        return std::any_of(host.loggedWarnings().begin(), host.loggedWarnings().end(),
                           [&](const std::string& w) { return w.find(text) != std::string::npos; });
    }

    std::filesystem::path dir_;
    TestHost host;
    std::vector<float> albedo;
};

// What the tile square of st (s, t) reads: its tile's decoded colour, black where it has none.
std::array<float, 3> expectedIn(int u, int v) {
    auto tile = kTiles.find(1001 + u + 10 * v);
    if (tile == kTiles.end()) return {0, 0, 0};
    return {srgb8Exact(tile->second[0]), srgb8Exact(tile->second[1]), srgb8Exact(tile->second[2])};
}

// Whether `albedo` is `expected` to within what the block encoding and the 8-bit storage move it.
bool matches(std::array<float, 3> albedo, std::array<float, 3> expected, float tolerance) {
    for (size_t c = 0; c < 3; ++c)
        if (std::abs(albedo[c] - expected[c]) > tolerance) return false;
    return true;
}

void UdimTextureTest::expectEachSquareShowsItsTile(float tolerance) const {
    // Every pixel shows the tile of the square its centre lies in; a pixel whose centre lies
    // within a pixel of a seam may show the square across it, but never a blend or a third colour.
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const double s = kColumns * (x + 0.5) / kWidth, t = kRows * (1.0 - (y + 0.5) / kHeight);
            const double pixelS = kColumns / kWidth, pixelT = kRows / kHeight;
            std::vector<std::array<float, 3>> allowed;
            for (double ds : {-pixelS, 0.0, pixelS})
                for (double dt : {-pixelT, 0.0, pixelT}) {
                    const double ns = std::clamp(s + ds, 0.0, kColumns - 1e-9), nt = std::clamp(t + dt, 0.0, kRows - 1e-9);
                    allowed.push_back(expectedIn(int(std::floor(ns)), int(std::floor(nt))));
                }
            const std::array<float, 3> seen = albedoAt(x, y);
            const bool ok = std::any_of(allowed.begin(), allowed.end(),
                                        [&](const auto& colour) { return matches(seen, colour, tolerance); });
            EXPECT_TRUE(ok) << "pixel (" << x << ", " << y << ") at st (" << s << ", " << t << ") reads (" << seen[0]
                            << ", " << seen[1] << ", " << seen[2] << ")";
        }
}

TEST_F(UdimTextureTest, EachTileShowsInItsSquareWithoutBleedingAcrossSeams) {
    setCompression(false);
    const std::string pattern = writeTiles();
    addPlane(pattern);
    render();
    // Square centres: exactly their tile (one step of the sRGB storage); the missing tile's
    // square reads transparent black, as Storm reads a missing tile.
    for (int v = 0; v < 2; ++v)
        for (int u = 0; u < 3; ++u) {
            const int x = int((u + 0.5) / kColumns * kWidth), y = int((1.0 - (v + 0.5) / kRows) * kHeight);
            EXPECT_TRUE(matches(albedoAt(x, y), expectedIn(u, v), 0.01f)) << "tile " << 1001 + u + 10 * v;
        }
    EXPECT_TRUE(matches(albedoAt(32, 16), {0, 0, 0}, 1e-4f)) << "missing tile " << kMissingTile;
    expectEachSquareShowsItsTile(0.01f);
    EXPECT_FALSE(warned(pattern));
    EXPECT_EQ(std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(),
                            [&](const std::string& m) { return m.rfind("loaded texture " + pattern + " ", 0) == 0; }),
              1);
}

TEST_F(UdimTextureTest, BlockCompressedTilesStayInTheirSquares) {
    setCompression(true);
    addPlane(writeTiles());
    render();
    // BC3 (the missing square is transparent) of solid colours: within a few codes.
    expectEachSquareShowsItsTile(0.03f);
}

TEST_F(UdimTextureTest, PatternWithoutTilesWarnsAndKeepsTheConstant) {
    const std::string pattern = (dir_ / "none.<UDIM>.png").string();
    addPlane(pattern, {0.25f, 0.5f, 0.75f});
    render();
    EXPECT_TRUE(matches(albedoAt(32, 32), {0.25f, 0.5f, 0.75f}, 0.01f));
    EXPECT_TRUE(warned("/Looks/M")) << "no warning names the material";
    EXPECT_TRUE(warned(pattern)) << "no warning names " << pattern;
}

TEST_F(UdimTextureTest, UnreadableTileIsReportedAndReadsAsMissing) {
    setCompression(false);
    const std::string pattern = writeTiles();
    const std::string broken = (dir_ / "body.1012.png").string();
    std::FILE* f = std::fopen(broken.c_str(), "wb");
    ASSERT_TRUE(f);
    std::fputs("not an image", f);
    std::fclose(f);
    addPlane(pattern);
    render();
    EXPECT_TRUE(warned(broken)) << "no warning names " << broken;
    EXPECT_TRUE(matches(albedoAt(32, 16), {0, 0, 0}, 1e-4f));
    EXPECT_TRUE(matches(albedoAt(10, 48), expectedIn(0, 0), 0.01f));
}

}  // namespace
}  // namespace obscura::test
