// UsdUVTexture textures end to end through the ABI: image files written here, bound to material
// inputs through the obscura:<input>:* attributes, looked up with the mesh's primvars:st, and
// read back from the albedo, color and primId AOVs. The camera sees exactly the unit st square
// of a plane, so pixel (x, y) shows st ((x + 0.5) / 64, 1 - (y + 0.5) / 64) times the st range.
#include "harness/image/exr_writer.h"
#include "harness/image/png_io.h"
#include "tests/delegate/camera_scene.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>

namespace obscura::test {
namespace {

constexpr double kDistance = 5.0;
constexpr float kFocalLength = 50.0f, kAperture = 20.955f;
const float kHalf = float(kAperture / 2.0 / kFocalLength * kDistance);  // the plane fills the view

using Rgb8 = std::array<uint8_t, 3>;
// The test image's four blocks: top left, top right, bottom left, bottom right.
constexpr std::array<Rgb8, 4> kBlocks = {{{200, 40, 40}, {40, 200, 40}, {40, 40, 200}, {220, 220, 60}}};

HostValue float4(float x, float y, float z, float w) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT4;
    h.floats = {x, y, z, w};
    return h;
}

// A material whose `input` reads `file`, with further obscura:<input>:<field> values.
std::map<std::string, HostValue> textured(const std::string& input, const std::string& file,
                                          const std::map<std::string, HostValue>& fields = {}) {
    std::map<std::string, HostValue> values = {{"obscura:" + input + ":file", HostValue::token(file)}};
    for (const auto& [field, value] : fields) values["obscura:" + input + ":" + field] = value;
    return values;
}

// One step of the 8-bit sRGB albedo target at `linear`: the storage's rounding.
float srgbStep(float linear) {
    int code = std::clamp(int(std::lround(srgbEncode(std::clamp(linear, 0.0f, 1.0f)) * 255.0f)), 0, 254);
    return srgb8Exact(code + 1) - srgb8Exact(code);
}

std::array<float, 3> decoded(Rgb8 c) { return {srgb8Exact(c[0]), srgb8Exact(c[1]), srgb8Exact(c[2])}; }
std::array<float, 3> raw(Rgb8 c) { return {c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f}; }

class TextureTest : public ::testing::Test {
protected:
    TextureTest() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("obscura_texture_" + std::string(info->name()) + "_" + std::to_string(getpid()));
        std::filesystem::create_directories(dir_);
        host.addCamera("/Camera", translation(0, 0, kDistance), kFocalLength, kAperture);
        for (const char* aov : {"albedo", "color"})
            host.addRenderBuffer(std::string("/Buffers/") + aov,
                                 std::string("float32Vec") + (aov[0] == 'a' ? "3" : "4"), kWidth, kHeight);
        host.addRenderBuffer("/Buffers/primId", "int32", kWidth, kHeight);
        // These tests check texel values to a step of the 8-bit storage; block compression, which
        // moves them further, has its own tests.
        setCompression(false);
    }
    ~TextureTest() override { std::filesystem::remove_all(dir_); }

    void setNumber(const char* key, double value) {
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &value};
        ASSERT_EQ(host.api().setRenderSetting(host.delegate(), key, &v), OBSCURA_OK);
    }
    void setCompression(bool on) {
        int32_t flag = on ? 1 : 0;
        ObscuraValue v{OBSCURA_VALUE_BOOL, 0, 1, &flag};
        ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "textures:compression", &v), OBSCURA_OK);
    }

    // An RGB PNG of `size` x `size` texels coloured by texel(x, y), row 0 at the top.
    std::string writePng(const std::string& name, int size, const std::function<Rgb8(int, int)>& texel) {
        std::vector<uint8_t> bytes;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                Rgb8 c = texel(x, y);
                bytes.insert(bytes.end(), c.begin(), c.end());
            }
        std::string path = (dir_ / name).string();
        auto written = image::writePng(path, size, size, image::PngFormat::Rgb, bytes.data(), size_t(size) * 3);
        EXPECT_FALSE(image::isError(written)) << image::errorOf(written);
        return path;
    }
    // 8x8 texels in four 4x4 blocks: bilinear lookups inside a block see only its colour.
    std::string writeBlocks(const std::string& name, const std::array<Rgb8, 4>& blocks = kBlocks) {
        return writePng(name, 8, [&](int x, int y) { return blocks[size_t(y / 4 * 2 + x / 4)]; });
    }

    // A square plane at z = 0 (by default exactly the camera's view) with st from 0 to stMax.
    void addPlane(const std::string& path, const std::string& material, float stMax = 1.0f, double centreX = 0.0,
                  float half = kHalf, std::map<std::string, HostValue> extra = {}) {
        extra["points"] = HostValue::points({{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}});
        extra["faceVertexCounts"] = HostValue::intArray({4});
        extra["faceVertexIndices"] = HostValue::intArray({0, 1, 2, 3});
        extra.emplace("subdivisionScheme", HostValue::token("none"));
        extra["primvars:st"] = HostValue::float2Array({{0, 0}, {stMax, 0}, {stMax, stMax}, {0, stMax}});
        extra["material:binding"] = HostValue::path(material);
        host.addPrim("mesh", path, extra, translation(centreX, 0, 0));
    }

    void render() {
        ASSERT_EQ(
            host.render("/Camera",
                        {{"albedo", "/Buffers/albedo"}, {"color", "/Buffers/color"}, {"primId", "/Buffers/primId"}}),
            OBSCURA_OK)
            << host.lastError();
        ASSERT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
        albedo = host.readFloats("/Buffers/albedo");
        color = host.readFloats("/Buffers/color");
        primIds = host.readInts("/Buffers/primId");
    }
    // Normal maps tilted along each map axis, lit along and against where the tilt must point.
    void expectNormalMapTilts(const std::map<std::string, HostValue>& lookup, std::array<int, 2> worldAxis,
                              std::array<double, 2> worldSign);

    void markDirty(const std::string& path, ObscuraDirtyBits bits = OBSCURA_DIRTY_PARAMS) {
        ASSERT_EQ(host.api().markDirty(host.delegate(), path.c_str(), bits), OBSCURA_OK);
    }

    void expectAlbedo(int x, int y, std::array<float, 3> expected, const std::string& what = "") {
        const float* p = &albedo[(size_t(y) * kWidth + size_t(x)) * 3];
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(p[c], expected[c], srgbStep(expected[c]) + 1e-4f)
                << what << " pixel (" << x << ", " << y << ") channel " << c;
    }
    const float* colorAt(int x, int y) const { return &color[(size_t(y) * kWidth + size_t(x)) * 4]; }

    size_t loadsOf(const std::string& file) const {
        return size_t(std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(), [&](const std::string& m) {
            return m.rfind("loaded texture " + file + " ", 0) == 0;
        }));
    }

    std::filesystem::path dir_;
    TestHost host;
    std::vector<float> albedo, color;
    std::vector<int32_t> primIds;
};

TEST_F(TextureTest, EachQuadrantShowsItsBlock) {
    std::string file = writeBlocks("blocks.png");
    host.addPrim("material", "/Looks/M", textured("diffuseColor", file));
    addPlane("/Plane", "/Looks/M");
    render();
    // An RGB PNG in "auto" is sRGB-encoded: the albedo is each block's decoded colour.
    for (int y : {8, 16, 23})
        for (int x : {8, 16, 23}) {
            expectAlbedo(x, y, decoded(kBlocks[0]), "top left");
            expectAlbedo(x + 32, y, decoded(kBlocks[1]), "top right");
            expectAlbedo(x, y + 32, decoded(kBlocks[2]), "bottom left");
            expectAlbedo(x + 32, y + 32, decoded(kBlocks[3]), "bottom right");
        }
    EXPECT_EQ(loadsOf(file), 1u);
}

// The block a lookup at (s, t) lands in under a UsdUVTexture wrap mode, or -1 for black.
int expectedBlock(double s, double t, const std::string& wrap) {
    auto fold = [&](double c) {
        if (wrap == "repeat") return c - std::floor(c);
        if (wrap == "clamp") return std::clamp(c, 0.0, 1.0);
        double m = std::fmod(c, 2.0);  // mirror: period 2, the second copy reversed
        return m > 1.0 ? 2.0 - m : m;
    };
    if (wrap == "black" && (s < 0 || s > 1 || t < 0 || t > 1)) return -1;
    double u = fold(s), v = 1.0 - fold(t);  // image rows run down from t = 1
    return (v < 0.5 ? 0 : 2) + (u < 0.5 ? 0 : 1);
}

TEST_F(TextureTest, WrapModesOutsideTheUnitSquare) {
    std::string file = writeBlocks("blocks.png");
    host.addPrim("material", "/Looks/M", textured("diffuseColor", file));
    addPlane("/Plane", "/Looks/M", 2.0f);
    for (std::string wrap : {"repeat", "clamp", "mirror", "black"}) {
        host.set("/Looks/M", "obscura:diffuseColor:wrapS", HostValue::token(wrap));
        host.set("/Looks/M", "obscura:diffuseColor:wrapT", HostValue::token(wrap));
        markDirty("/Looks/M");
        render();
        // The centres of 16-pixel cells: st in [0, 2] over 64 pixels puts them mid-block.
        for (int y = 8; y < kHeight; y += 16)
            for (int x = 8; x < kWidth; x += 16) {
                int block = expectedBlock((x + 0.5) / 32.0, 2.0 - (y + 0.5) / 32.0, wrap);
                expectAlbedo(x, y, block < 0 ? std::array<float, 3>{0, 0, 0} : decoded(kBlocks[size_t(block)]), wrap);
            }
    }
    // Repeat shows the pattern twice across: the top-left block again at the second cell pair.
    EXPECT_EQ(expectedBlock(40.5 / 32.0, 2.0 - 8.5 / 32.0, "repeat"), 0);
}

// The rows of an affine map of st, as obscura:<input>:transformS and transformT hold them.
struct StMap {
    std::array<float, 3> s, t;
    std::array<double, 2> operator()(double u, double v) const {
        return {s[0] * u + s[1] * v + s[2], t[0] * u + t[1] * v + t[2]};
    }
};

std::map<std::string, HostValue> transformed(const StMap& map) {
    return {{"transformS", HostValue::float3(map.s[0], map.s[1], map.s[2])},
            {"transformT", HostValue::float3(map.t[0], map.t[1], map.t[2])}};
}

// UsdTransform2d's st' = translation + rotate(rotation) (scale st): scale (2, 2) tiles the blocks
// twice, rotation 90 degrees turns them counter-clockwise, a translation shifts them. Each cell
// centre shows the block its transformed st falls in (the default wrap repeats).
TEST_F(TextureTest, TransformedCoordinatesTileRotateAndShiftTheTexture) {
    std::string file = writeBlocks("blocks.png");
    const std::vector<std::pair<std::string, StMap>> cases = {
        {"scale (2, 2)", {{2, 0, 0}, {0, 2, 0}}},
        {"rotation 90", {{0, -1, 0}, {1, 0, 0}}},
        {"translation (0.25, 0.5)", {{1, 0, 0.25f}, {0, 1, 0.5f}}},
    };
    host.addPrim("material", "/Looks/M", textured("diffuseColor", file));
    addPlane("/Plane", "/Looks/M");
    for (const auto& [what, map] : cases) {
        for (const auto& [field, value] : transformed(map))
            host.set("/Looks/M", "obscura:diffuseColor:" + field, value);
        markDirty("/Looks/M");
        render();
        int differs = 0;  // cells where the untransformed texture would show another block
        for (int y = 8; y < kHeight; y += 16)
            for (int x = 8; x < kWidth; x += 16) {
                const double s = (x + 0.5) / kWidth, t = 1.0 - (y + 0.5) / kHeight;
                const auto [s2, t2] = map(s, t);
                const int block = expectedBlock(s2, t2, "repeat");
                expectAlbedo(x, y, decoded(kBlocks[size_t(block)]), what);
                differs += block != expectedBlock(s, t, "repeat");
            }
        EXPECT_GE(differs, 8) << what << " moves the blocks";
    }
}

// The forward pass of transparent surfaces samples through the same map: an opacity mask, quarter
// opaque on the left half of the image and opaque on the right, turned 90 degrees puts the
// quarter-opaque half at the top; over the empty background the colour's alpha is the opacity.
TEST_F(TextureTest, TransparentSurfacesSampleThroughTheTransformToo) {
    std::string file = writePng("mask.png", 8, [](int x, int) { return x < 4 ? Rgb8{64, 64, 64} : Rgb8{255, 255, 255}; });
    std::map<std::string, HostValue> values = textured(
        "opacity", file, {{"sourceColorSpace", HostValue::token("raw")}, {"transformS", HostValue::float3(0, -1, 0)},
                          {"transformT", HostValue::float3(1, 0, 0)}});
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    render();
    for (int x : {8, 24, 40, 56}) {
        EXPECT_NEAR(colorAt(x, 16)[3], 64.0f / 255.0f, 2.0f / 255.0f) << "top half, column " << x;
        EXPECT_NEAR(colorAt(x, 48)[3], 1.0f, 2.0f / 255.0f) << "bottom half, column " << x;
    }
    EXPECT_EQ(primIds[size_t(32) * kWidth + 32], -1) << "the plane is transparent, drawn forward";
}

// Non-finite rows are bad data, reported like other bad material inputs: the material is skipped.
TEST_F(TextureTest, NonFiniteTransformIsReported) {
    std::string file = writeBlocks("blocks.png");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    host.addPrim("material", "/Looks/M", textured("diffuseColor", file, {{"transformT", HostValue::float3(0, nan, 0)}}));
    addPlane("/Plane", "/Looks/M");
    host.expectError("skipped prim /Looks/M: obscura:diffuseColor:transformT: value is NaN");
    EXPECT_EQ(host.render("/Camera", {{"albedo", "/Buffers/albedo"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
    EXPECT_NE(host.lastError().find("/Looks/M"), std::string::npos) << host.lastError();
}

TEST_F(TextureTest, ScaleAndBiasTransformTheTexel) {
    std::string file = writeBlocks("blocks.png");
    host.addPrim("material", "/Looks/M",
                 textured("diffuseColor", file,
                          {{"sourceColorSpace", HostValue::token("raw")},
                           {"scale", float4(0.5f, 2.0f, 1.0f, 1.0f)},
                           {"bias", float4(0.1f, -0.1f, 0.05f, 0.0f)}}));
    addPlane("/Plane", "/Looks/M");
    render();
    // UsdUVTexture: out = texel * scale + bias, per channel.
    for (size_t block = 0; block < 4; ++block) {
        auto t = raw(kBlocks[block]);
        std::array<float, 3> expected = {t[0] * 0.5f + 0.1f, std::min(t[1] * 2.0f - 0.1f, 1.0f), t[2] + 0.05f};
        expectAlbedo(block % 2 ? 48 : 16, block < 2 ? 16 : 48, expected, "block " + std::to_string(block));
    }
}

TEST_F(TextureTest, SourceColorSpaceDecidesHowTexelsDecode) {
    std::string file = writePng("grey.png", 4, [](int, int) { return Rgb8{128, 64, 200}; });
    const float half = kHalf / 3.0f;
    const std::array<std::string, 3> spaces = {"sRGB", "raw", "auto"};
    for (size_t i = 0; i < spaces.size(); ++i) {
        std::string material = "/Looks/" + spaces[i];
        host.addPrim("material", material,
                     textured("diffuseColor", file, {{"sourceColorSpace", HostValue::token(spaces[i])}}));
        addPlane("/Plane" + spaces[i], material, 1.0f, (double(i) - 1.0) * 2.0 * half, half);
    }
    render();
    expectAlbedo(10, 32, decoded({128, 64, 200}), "sRGB");  // the sRGB curve: 128 -> 0.216
    expectAlbedo(32, 32, raw({128, 64, 200}), "raw");       // linear: 128 -> 0.502
    expectAlbedo(53, 32, decoded({128, 64, 200}), "auto");  // an 8-bit RGB file is sRGB
    EXPECT_EQ(loadsOf(file), 3u) << "one texture per colour space";
}

// Between the centres of a magnified texture's texels, an sRGB texture blends its encoded values
// and decodes after, as offline renderers reconstruct 8-bit textures (Cycles interpolates the
// bytes): a black and a white texel stretched over the image meet at decode(1/2) = 0.214 halfway,
// where a blend of linear values would read 0.5. One frame without temporal AA: each pixel looks
// up its centre.
TEST_F(TextureTest, MagnifiedTexelsBlendInTheirEncoding) {
    std::string file = writePng("ramp.png", 2, [](int x, int) { return x == 0 ? Rgb8{0, 0, 0} : Rgb8{255, 255, 255}; });
    host.addPrim("material", "/Looks/M",
                 textured("diffuseColor", file, {{"wrapS", HostValue::token("clamp")}, {"wrapT", HostValue::token("clamp")}}));
    addPlane("/Plane", "/Looks/M");
    setNumber("taa", 0.0);
    render();
    for (int x = 12; x < 52; x += 4) {
        // Texel coordinates: the centres of the two texels at 0.5 and 1.5.
        const double between = std::clamp(2.0 * (x + 0.5) / kWidth - 0.5, 0.0, 1.0);
        const float expected = srgbDecode(between);
        const float* p = &albedo[(size_t(32) * kWidth + size_t(x)) * 3];
        // The albedo target's 8-bit step and one more for the filter's 8-bit weights.
        for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected, 2.0f * srgbStep(expected) + 1e-4f) << "column " << x;
    }
}

TEST_F(TextureTest, ScalarTexturesMatchTheirConstants) {
    // 51 / 255 = 0.2 exactly: a texture of it must light exactly as the constant 0.2.
    std::string file = writePng("point2.png", 4, [](int, int) { return Rgb8{51, 51, 51}; });
    std::string white = writePng("white.png", 4, [](int, int) { return Rgb8{255, 255, 255}; });
    // Straight down: the plane's centre mirrors the light into the camera, where the specular
    // lobe's peak (1 / (pi alpha^2) for GGX) depends most on roughness.
    host.addPrim("distantLight", "/Sun",
                 {{"inputs:intensity", HostValue::floatValue(2.0f)}, {"inputs:normalize", HostValue::boolean(true)}},
                 lightPointingAlong({0.0, 0.0, -1.0}));
    addMaterial(host, "/Looks/M", {0.5f, 0.5f, 0.5f}, 1.0f, 0.0f);
    addPlane("/Plane", "/Looks/M");
    struct Case {
        std::string input;
        std::string file;
        float textured;  // the texture's value
        float other;     // a constant that looks different
    };
    for (const Case& c : {Case{"roughness", file, 0.2f, 1.0f}, Case{"metallic", white, 1.0f, 0.0f}}) {
        auto centreWith = [&](const std::string& textureFile, float constant) {
            host.set("/Looks/M", "obscura:" + c.input + ":file", HostValue::token(textureFile));
            host.set("/Looks/M", "obscura:" + c.input + ":sourceColorSpace", HostValue::token("raw"));
            host.set("/Looks/M", "inputs:" + c.input, HostValue::floatValue(constant));
            markDirty("/Looks/M");
            render();
            const float* p = colorAt(32, 32);
            return std::array<float, 3>{p[0], p[1], p[2]};
        };
        auto texturedColour = centreWith(c.file, c.other);  // the texture wins over the constant
        auto constantColour = centreWith("", c.textured);
        auto otherColour = centreWith("", c.other);
        for (size_t ch = 0; ch < 3; ++ch) {
            float e = constantColour[ch];
            EXPECT_NEAR(texturedColour[ch], e, 0.01f * e + smallFloatStep(e, 5)) << c.input;
            EXPECT_GT(std::fabs(otherColour[ch] - e), 0.1f * e) << c.input << " made no difference";
        }
    }
}

TEST_F(TextureTest, OpacityTextureCutsOutBelowTheThreshold) {
    std::string file = writePng("mask.png", 8, [](int x, int) { return x < 4 ? Rgb8{0, 0, 0} : Rgb8{255, 255, 255}; });
    std::map<std::string, HostValue> values =
        textured("opacity", file, {{"sourceColorSpace", HostValue::token("raw")}});
    values["inputs:opacityThreshold"] = HostValue::floatValue(0.5f);
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    render();
    int32_t plane = -1;
    ASSERT_EQ(host.api().getPrimId(host.delegate(), "/Plane", &plane), OBSCURA_OK);
    for (int y : {4, 32, 60}) {
        EXPECT_EQ(primIds[size_t(y) * kWidth + 10], -1) << "transparent half drawn at row " << y;
        EXPECT_EQ(primIds[size_t(y) * kWidth + 54], plane) << "opaque half missing at row " << y;
    }
}

// Alpha-test supersampling (seed 000 "Deferred MSAA \ alpha test SSAA"): a glowing plane cut out
// by a disc in its opacity texture. The disc's edge lies inside one triangle, where the
// rasteriser's coverage sees no edge: with 4 samples each sample tests the opacity at its own
// position, and the edge converges toward the 8x supersampled image; alpha-to-coverage (the
// setting msaa:alphaToCoverage) from one lookup gets part of the way.
TEST_F(TextureTest, CutOutEdgesAreSupersampledPerSample) {
    constexpr int kTexels = 256, kSuper = 8;
    std::string file = writePng("disc.png", kTexels, [](int x, int y) {
        double dx = (x + 0.5) / kTexels - 0.5, dy = (y + 0.5) / kTexels - 0.45;
        uint8_t v = dx * dx + dy * dy < 0.3 * 0.3 ? 255 : 0;
        return Rgb8{v, v, v};
    });
    std::map<std::string, HostValue> values = textured("opacity", file, {{"sourceColorSpace", HostValue::token("raw")}});
    values["inputs:opacityThreshold"] = HostValue::floatValue(0.5f);
    values["inputs:diffuseColor"] = HostValue::float3(0, 0, 0);
    values["inputs:emissiveColor"] = HostValue::float3(1, 1, 1);
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    host.addRenderBuffer("/Buffers/super", "float32Vec4", kWidth * kSuper, kHeight * kSuper);
    auto set = [&](const char* name, double value) {
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &value};
        ASSERT_EQ(host.api().setRenderSetting(host.delegate(), name, &v), OBSCURA_OK) << host.lastError();
    };
    set("taa", 0);
    set("ssao", 0);
    auto renderInto = [&](const char* buffer) {
        EXPECT_EQ(host.render("/Camera", {{"color", buffer}}), OBSCURA_OK) << host.lastError();
        return host.readFloats(buffer);
    };
    image::Image truth = boxDownsample(renderInto("/Buffers/super"), kWidth * kSuper, kHeight * kSuper, kSuper);
    image::CompareMetrics one = compareImages(rgbImage(renderInto("/Buffers/color"), kWidth, kHeight), truth);
    set("msaa", 4);
    image::CompareMetrics perSample = compareImages(rgbImage(renderInto("/Buffers/color"), kWidth, kHeight), truth);
    set("msaa:alphaToCoverage", 1);
    image::CompareMetrics toCoverage = compareImages(rgbImage(renderInto("/Buffers/color"), kWidth, kHeight), truth);
    std::printf("[ metric ] cut-out disc vs %dx supersampled: msaa 1 %.2f dB SSIM %.4f; msaa 4 alpha-test SSAA "
                "%.2f dB SSIM %.4f; msaa 4 alpha-to-coverage %.2f dB SSIM %.4f\n",
                kSuper, one.psnr, one.ssim, perSample.psnr, perSample.ssim, toCoverage.psnr, toCoverage.ssim);
    EXPECT_GT(perSample.psnr, one.psnr + 4.0);
    EXPECT_GT(toCoverage.psnr, one.psnr + 1.0);
}

TEST_F(TextureTest, OcclusionTextureDarkensTheDomeWhereItSaysSo) {
    // Left half 255 (unoccluded), right half 128 (raw: 0.502): the dome lights the right half half
    // as much (UsdPreviewSurface occlusion darkens indirect light only). SSAO off: a flat plane.
    std::string file =
        writePng("occlusion.png", 8, [](int x, int) { return x < 4 ? Rgb8{255, 255, 255} : Rgb8{128, 128, 128}; });
    std::map<std::string, HostValue> values =
        textured("occlusion", file, {{"sourceColorSpace", HostValue::token("raw")}});
    values["inputs:diffuseColor"] = HostValue::float3(0.5f, 0.5f, 0.5f);
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    host.addPrim("domeLight", "/Sky",
                 {{"inputs:intensity", HostValue::floatValue(1.0f)}, {"inputs:specular", HostValue::floatValue(0.0f)}});
    double off = 0.0;
    ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &off};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "ssao", &v), OBSCURA_OK);
    render();
    for (int y : {10, 32, 54}) {
        float open = colorAt(10, y)[0], occluded = colorAt(54, y)[0];
        if (y == 32) std::printf("[ metric ] occlusion texture: right / left radiance %.4f (texel 128/255 = %.4f)\n",
                                 double(occluded / open), 128.0 / 255.0);
        EXPECT_NEAR(open, 0.5f, 0.01f + smallFloatStep(0.5f, 6)) << "row " << y;
        EXPECT_NEAR(occluded / open, 128.0f / 255.0f, 0.01f + 2.0f * smallFloatStep(1.0f, 6)) << "row " << y;
    }
}

// A textured emissiveColor emits its texels (the G-buffer's emission target; the transparent
// pass samples it itself): left half red, right half blue, raw, scale 2, on a black surface in
// the dark. Its average, (1, 0, 1), is what each pixel used to get.
class EmissiveTexture : public TextureTest {
protected:
    EmissiveTexture() {
        file = writePng("glow.png", 8, [](int x, int) { return x < 4 ? Rgb8{255, 0, 0} : Rgb8{0, 0, 255}; });
        values = textured("emissiveColor", file,
                          {{"sourceColorSpace", HostValue::token("raw")}, {"scale", float4(2, 2, 2, 1)}});
        values["inputs:diffuseColor"] = HostValue::float3(0, 0, 0);
    }
    // Each half's pixels away from the middle: `radiance` of red, then of blue.
    void expectHalves(float radiance, const std::string& what) {
        for (int x : {10, 24, 40, 54}) {
            const float* p = colorAt(x, 32);
            const bool red = x < 32;
            EXPECT_NEAR(p[0], red ? radiance : 0.0f, 0.01f + smallFloatStep(radiance, 6)) << what << ", x " << x;
            EXPECT_NEAR(p[1], 0.0f, 1e-4f) << what << ", x " << x;
            EXPECT_NEAR(p[2], red ? 0.0f : radiance, 0.01f + smallFloatStep(radiance, 5)) << what << ", x " << x;
        }
    }
    std::string file;
    std::map<std::string, HostValue> values;
};

TEST_F(EmissiveTexture, OpaqueSurfacesEmitTheirTexels) {
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    ASSERT_NO_FATAL_FAILURE(render());
    expectHalves(2.0f, "1 sample");
    // With MSAA the lighting reads the multisampled target, per pixel and per tagged sample.
    setNumber("msaa", 4);
    ASSERT_NO_FATAL_FAILURE(render());
    expectHalves(2.0f, "msaa 4");
    // With motion blur the G-buffer has a velocity target (RT3) before the emission: a small
    // plane moving across the top of the image, in front, turns it on.
    setNumber("msaa", 1);
    host.set("/Camera", "shutter:open", HostValue::doubleValue(-0.25));
    host.set("/Camera", "shutter:close", HostValue::doubleValue(0.25));
    ASSERT_EQ(host.api().markDirty(host.delegate(), "/Camera", OBSCURA_DIRTY_PARAMS), OBSCURA_OK);
    addPlane("/Mover", "/Looks/M", 1.0f, 0.0, 0.1f * kHalf);
    host.setTransformMotion("/Mover", -0.5, translation(-0.6 * kHalf, 0.8 * kHalf, 0.1), 0.5,
                            translation(-0.4 * kHalf, 0.8 * kHalf, 0.1));
    ASSERT_NO_FATAL_FAILURE(render());
    EXPECT_TRUE(ranPass(host, "motion_blur_tile_max"));
    expectHalves(2.0f, "with motion blur");
}

TEST_F(EmissiveTexture, TransparentSurfacesEmitTheirTexelsTimesTheirOpacity) {
    values["inputs:opacity"] = HostValue::floatValue(0.5f);
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    ASSERT_NO_FATAL_FAILURE(render());
    expectHalves(1.0f, "opacity 0.5");
}

TEST_F(TextureTest, MissingFileWarnsAndKeepsTheConstant) {
    std::string missing = (dir_ / "no-such-texture.png").string();
    std::map<std::string, HostValue> values = textured("diffuseColor", missing);
    float grey = srgb8Exact(150);
    values["inputs:diffuseColor"] = HostValue::float3(grey, grey, grey);
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    render();
    expectAlbedo(32, 32, {grey, grey, grey});
    bool warned = std::any_of(host.loggedWarnings().begin(), host.loggedWarnings().end(),
                              [&](const std::string& w) { return w.find(missing) != std::string::npos; });
    EXPECT_TRUE(warned) << "no warning names " << missing;
}

TEST_F(TextureTest, UnreadableNormalMapWarnsAndKeepsTheGeometricNormal) {
    // A file that is no image, bound as a two-channel normal map (raw, 2 n - 1): a warning names
    // it and the surface shades with its own normal, as unmapped.
    const std::string broken = (dir_ / "broken_normal.png").string();
    std::FILE* f = std::fopen(broken.c_str(), "wb");
    ASSERT_TRUE(f);
    std::fputs("not an image", f);
    std::fclose(f);
    auto values = textured("normal", broken, {{"sourceColorSpace", HostValue::token("raw")},
                                              {"channel", HostValue::token("rgb")},
                                              {"scale", float4(2.0f, 2.0f, 2.0f, 1.0f)},
                                              {"bias", float4(-1.0f, -1.0f, -1.0f, 0.0f)}});
    const float grey = srgb8Exact(150);
    values["inputs:diffuseColor"] = HostValue::float3(grey, grey, grey);
    host.addPrim("material", "/Looks/M", values);
    addPlane("/Plane", "/Looks/M");
    host.addPrim("distantLight", "/Sun",
                 {{"inputs:intensity", HostValue::floatValue(1.0f)},
                  {"inputs:normalize", HostValue::boolean(true)},
                  {"inputs:specular", HostValue::floatValue(0.0f)}},
                 lightPointingAlong({0.0, 0.0, -1.0}));
    render();
    const double expected = grey / kPi;
    EXPECT_NEAR(colorAt(32, 32)[0], expected, 0.01 * expected + smallFloatStep(float(expected), 6));
    EXPECT_TRUE(std::any_of(host.loggedWarnings().begin(), host.loggedWarnings().end(),
                            [&](const std::string& w) { return w.find(broken) != std::string::npos; }))
        << "no warning names " << broken;
}

TEST_F(TextureTest, MaterialsSharingAFileLoadItOnce) {
    std::string file = writeBlocks("blocks.png");
    host.addPrim("material", "/Looks/A", textured("diffuseColor", file));
    host.addPrim("material", "/Looks/B", textured("diffuseColor", file, {{"wrapS", HostValue::token("clamp")}}));
    addPlane("/Left", "/Looks/A", 1.0f, -kHalf / 2.0, kHalf / 2.0f);
    addPlane("/Right", "/Looks/B", 1.0f, kHalf / 2.0, kHalf / 2.0f);
    render();
    EXPECT_EQ(loadsOf(file), 1u);
    // Both draw the whole texture in their half of the view.
    expectAlbedo(8, 40, decoded(kBlocks[2]), "left plane");
    expectAlbedo(56, 24, decoded(kBlocks[1]), "right plane");
}

TEST_F(TextureTest, OpenExrTexturesAreLinearHalfFloats) {
    const std::array<std::array<float, 4>, 4> blocks = {
        {{0.25f, 0.5f, 0.75f, 1}, {1.0f, 0.5f, 0.0f, 1}, {0.05f, 0.1f, 0.2f, 1}, {0.6f, 0.6f, 0.6f, 1}}};
    std::vector<float> texels;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const auto& b = blocks[size_t(y / 4 * 2 + x / 4)];
            texels.insert(texels.end(), b.begin(), b.end());
        }
    std::string file = (dir_ / "blocks.exr").string();
    image::ExrLayer layer{
        "", {"R", "G", "B", "A"}, image::ExrLayer::PixelType::Half, texels.data(), 8 * 4 * sizeof(float)};
    ASSERT_FALSE(image::isError(image::writeExr(file, 8, 8, {layer})));
    host.addPrim("material", "/Looks/M",
                 textured("diffuseColor", file, {{"sourceColorSpace", HostValue::token("sRGB")}}));
    addPlane("/Plane", "/Looks/M");
    render();
    for (size_t block = 0; block < 4; ++block)
        expectAlbedo(block % 2 ? 48 : 16, block < 2 ? 16 : 48, {blocks[block][0], blocks[block][1], blocks[block][2]},
                     "block " + std::to_string(block));
    ASSERT_EQ(loadsOf(file), 1u);
}

// A constant tangent-space normal tilted 30 degrees towards +u (then towards +v), stored as it is
// in a float EXR (scale 1, bias 0), looked up through `lookup` (the texture's transform, if any).
// u runs along +X and v along +Y on the plane; the shading normal must tilt towards world axis
// worldAxis[k] (0: X, 1: Y) with sign worldSign[k] for the map's axis k: a distant light along that
// normal gives the full E albedo / pi, one mirrored about the plane's normal cos 60 of it (unmapped:
// cos 30 both).
void TextureTest::expectNormalMapTilts(const std::map<std::string, HostValue>& lookup,
                                       std::array<int, 2> worldAxis, std::array<double, 2> worldSign) {
    const float kAlbedo = srgb8Exact(188);
    const double tilt = 30.0 * kPi / 180.0;
    for (int axis = 0; axis < 2; ++axis) {
        std::array<float, 4> normal{0, 0, float(std::cos(tilt)), 1};
        normal[size_t(axis)] = float(std::sin(tilt));
        std::vector<float> texels;
        for (int i = 0; i < 16; ++i) texels.insert(texels.end(), normal.begin(), normal.end());
        std::string file = (dir_ / ("normal" + std::to_string(axis) + ".exr")).string();
        image::ExrLayer layer{"", {"R", "G", "B", "A"}, image::ExrLayer::PixelType::Float, texels.data(),
                              4 * 4 * sizeof(float)};
        ASSERT_FALSE(image::isError(image::writeExr(file, 4, 4, {layer})));
        std::string material = "/Looks/Bumped" + std::to_string(axis), plane = "/Plane" + std::to_string(axis);
        std::map<std::string, HostValue> fields{{"sourceColorSpace", HostValue::token("raw")},
                                                {"channel", HostValue::token("rgb")}};
        fields.insert(lookup.begin(), lookup.end());
        auto values = textured("normal", file, fields);
        values["inputs:diffuseColor"] = HostValue::float3(kAlbedo, kAlbedo, kAlbedo);
        host.addPrim("material", material, values);
        addPlane(plane, material);
        for (double side : {1.0, -1.0}) {
            std::array<double, 3> towards{0, 0, -std::cos(tilt)};
            towards[size_t(worldAxis[size_t(axis)])] = -side * worldSign[size_t(axis)] * std::sin(tilt);
            host.addPrim("distantLight", "/Sun",
                         {{"inputs:intensity", HostValue::floatValue(1.0f)},
                          {"inputs:normalize", HostValue::boolean(true)},
                          {"inputs:specular", HostValue::floatValue(0.0f)}},
                         lightPointingAlong(towards));
            render();
            double expected = kAlbedo / kPi * (side > 0 ? 1.0 : std::cos(2 * tilt));
            const float* p = colorAt(32, 32);
            // 1% plus a step of the light buffer, plus the 8-bit normal's 0.3 degrees at 60 degrees.
            double tolerance = 0.01 * expected + smallFloatStep(float(expected), 6) + 0.01 * expected;
            EXPECT_NEAR(p[0], expected, tolerance) << (axis ? "v" : "u") << " tilt, light " << (side > 0 ? "along" : "mirrored");
            ASSERT_EQ(host.api().removePrim(host.delegate(), "/Sun"), OBSCURA_OK);
        }
        ASSERT_EQ(host.api().removePrim(host.delegate(), plane.c_str()), OBSCURA_OK);
        ASSERT_EQ(host.api().removePrim(host.delegate(), material.c_str()), OBSCURA_OK);
    }
}

TEST_F(TextureTest, NormalMapsTiltTheShadingNormalInTheTangentFrame) {
    expectNormalMapTilts({}, {0, 1}, {1.0, 1.0});
}

// The texture turned 90 degrees counter-clockwise (UsdTransform2d rotation 90: s' = -t, t' = s):
// the map's +u now runs along the plane's -v (world -Y) and its +v along +u (world +X). A mirror
// (s' = -s) turns +u to world -X and keeps +v.
TEST_F(TextureTest, NormalMapsTurnWithTheirTextureTransform) {
    expectNormalMapTilts(transformed({{0, -1, 0}, {1, 0, 0}}), {1, 0}, {-1.0, 1.0});
    expectNormalMapTilts(transformed({{-1, 0, 0}, {0, 1, 0}}), {0, 1}, {-1.0, 1.0});
}

TEST_F(TextureTest, RenormalisedTextureRendersAsItsFloatReference) {
    // A low-contrast 16-bit sRGB gradient (red codes 0.40..0.46 along u, green 0.20..0.25 along v,
    // blue constant) is stored renormalised in 8 bits; the same linear values in a float EXR are
    // the reference. Both pass through the material's scale and bias, which the renormalisation
    // folds into; they must agree within a step of the 8-bit sRGB albedo target (clamped, so that
    // no lookup wraps to the far side of the gradient).
    constexpr int kTexels = 64;
    auto encoded = [](int x, int y) {
        return std::array<float, 3>{0.40f + 0.06f * float(x) / (kTexels - 1), 0.20f + 0.05f * float(y) / (kTexels - 1),
                                    0.7f};
    };
    std::vector<uint16_t> codes;
    std::vector<float> linear;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) {
            for (float e : encoded(x, y)) {
                codes.push_back(uint16_t(std::lround(e * 65535.0f)));
                linear.push_back(srgbDecode(codes.back() / 65535.0));
            }
            linear.push_back(1.0f);
        }
    std::string png = (dir_ / "low_contrast.png").string(), exr = (dir_ / "low_contrast.exr").string();
    ASSERT_FALSE(image::isError(image::writePng16(png, kTexels, kTexels, codes.data())));
    image::ExrLayer layer{"", {"R", "G", "B", "A"}, image::ExrLayer::PixelType::Float, linear.data(),
                          size_t(kTexels) * 4 * sizeof(float)};
    ASSERT_FALSE(image::isError(image::writeExr(exr, kTexels, kTexels, {layer})));
    std::vector<float> images[2];
    for (int i = 0; i < 2; ++i) {
        const std::string& file = i == 0 ? exr : png;
        host.addPrim("material", "/Looks/M",
                     textured("diffuseColor", file, {{"scale", float4(1.5f, 1.0f, 0.8f, 1.0f)},
                                                      {"bias", float4(0.0f, 0.05f, 0.0f, 0.0f)},
                                                      {"wrapS", HostValue::token("clamp")},
                                                      {"wrapT", HostValue::token("clamp")}}));
        addPlane("/Plane", "/Looks/M");
        render();
        images[i] = albedo;
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Plane"), OBSCURA_OK);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Looks/M"), OBSCURA_OK);
    }
    EXPECT_EQ(std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(),
                            [](const std::string& m) { return m.find("renormalised") != std::string::npos; }),
              1);
    // The outermost pixels are left out: each render's sub-pixel jitter may move the plane's edge
    // past them.
    for (int y = 1; y < kHeight - 1; ++y)
        for (int x = 1; x < kWidth - 1; ++x)
            for (size_t c = 0; c < 3; ++c) {
                const size_t i = (size_t(y) * kWidth + size_t(x)) * 3 + c;
                ASSERT_NEAR(images[1][i], images[0][i], srgbStep(images[0][i]) + 1e-4f)
                    << "pixel (" << x << ", " << y << ") channel " << c;
            }
}

TEST_F(TextureTest, TwoChannelNormalMapsShadeLikeTheirNormal) {
    // A constant normal tilted 30 degrees towards +u, stored as 0.5 n + 0.5 and read raw with
    // scale 2, bias -1: a 16-bit PNG is kept at 16 bits in two channels (RG16), an 8-bit one is
    // BC5-compressed, or with textures:compression off stays RGBA8 as it always was. In each the
    // shader's normal (z reconstructed where two channels are stored) faces a distant light along
    // the tilted normal: E albedo / pi, as in NormalMapsTiltTheShadingNormalInTheTangentFrame.
    const float kAlbedo = srgb8Exact(188);
    const double tilt = 30.0 * kPi / 180.0;
    const std::array<double, 3> stored{0.5 * std::sin(tilt) + 0.5, 0.5, 0.5 * std::cos(tilt) + 0.5};
    std::vector<uint16_t> codes16;
    for (int i = 0; i < 16; ++i)
        for (double v : stored) codes16.push_back(uint16_t(std::lround(v * 65535.0)));
    const std::string png16 = (dir_ / "normal16.png").string();
    ASSERT_FALSE(image::isError(image::writePng16(png16, 4, 4, codes16.data())));
    const std::string png8 = writePng("normal8.png", 4, [&](int, int) {
        return Rgb8{uint8_t(std::lround(stored[0] * 255.0)), uint8_t(std::lround(stored[1] * 255.0)),
                    uint8_t(std::lround(stored[2] * 255.0))};
    });
    host.addPrim("distantLight", "/Sun",
                 {{"inputs:intensity", HostValue::floatValue(1.0f)},
                  {"inputs:normalize", HostValue::boolean(true)},
                  {"inputs:specular", HostValue::floatValue(0.0f)}},
                 lightPointingAlong({-std::sin(tilt), 0.0, -std::cos(tilt)}));
    struct Case {
        std::string file;
        bool compression;
        const char* format;
    };
    for (const Case& c : {Case{png16, true, "RG16"}, Case{png8, true, "BC5"}, Case{png8, false, "RGBA8"}}) {
        setCompression(c.compression);
        auto values = textured("normal", c.file, {{"sourceColorSpace", HostValue::token("raw")},
                                                  {"channel", HostValue::token("rgb")},
                                                  {"scale", float4(2.0f, 2.0f, 2.0f, 1.0f)},
                                                  {"bias", float4(-1.0f, -1.0f, -1.0f, 0.0f)}});
        values["inputs:diffuseColor"] = HostValue::float3(kAlbedo, kAlbedo, kAlbedo);
        host.addPrim("material", "/Looks/Bumped", values);
        addPlane("/Plane", "/Looks/Bumped");
        render();
        const double expected = kAlbedo / kPi;
        // 1% plus a step of the light buffer: at the light's own direction the cosine is flat, so
        // the stored normal's fraction-of-a-degree error costs nothing visible.
        EXPECT_NEAR(colorAt(32, 32)[0], expected, 0.01 * expected + smallFloatStep(float(expected), 6)) << c.format;
        EXPECT_EQ(std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(),
                                [&](const std::string& m) {
                                    return m.rfind("loaded texture " + c.file + " (4x4 " + c.format + ",", 0) == 0;
                                }),
                  1)
            << c.format;
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Plane"), OBSCURA_OK);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Looks/Bumped"), OBSCURA_OK);
    }
}

TEST_F(TextureTest, BlockCompressedRampRendersWithinBc1sPrecision) {
    // A smooth sRGB colour ramp (one texel per pixel) rendered BC1-compressed and uncompressed:
    // BC1 follows a ramp's colours in each block but holds its endpoints to 5:6:5, at worst half
    // a 5-bit step (4.1 codes) off, so the albedo, read as sRGB codes, keeps a PSNR of at least
    // 20 log10(255 / 4.1) = 35.9 dB against the uncompressed render (35 dB asked, leaving room for
    // the albedo target's own rounding). Off, the texture is the RGBA8 sRGB it always was.
    const std::string file = writePng("ramp.png", 64, [](int x, int) {
        const float t = float(x) / 63.0f;
        return Rgb8{uint8_t(std::lround(20.0f + 210.0f * t)), uint8_t(std::lround(60.0f + 120.0f * t)),
                    uint8_t(std::lround(200.0f - 160.0f * t))};
    });
    std::vector<float> images[2];
    const char* formats[2] = {"RGBA8 sRGB", "BC1 sRGB"};
    for (int on = 0; on < 2; ++on) {
        setCompression(on == 1);
        host.addPrim("material", "/Looks/M",
                     textured("diffuseColor", file,
                              {{"wrapS", HostValue::token("clamp")}, {"wrapT", HostValue::token("clamp")}}));
        addPlane("/Plane", "/Looks/M");
        render();
        images[on] = albedo;
        EXPECT_EQ(std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(),
                                [&](const std::string& m) {
                                    return m.rfind("loaded texture " + file + " (64x64 " + formats[on] + ",", 0) == 0;
                                }),
                  1)
            << formats[on];
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Plane"), OBSCURA_OK);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Looks/M"), OBSCURA_OK);
    }
    // Interior pixels: each render's jitter may move the plane's edge past the outermost ones.
    double squared = 0.0;
    size_t count = 0;
    for (int y = 1; y < kHeight - 1; ++y)
        for (int x = 1; x < kWidth - 1; ++x)
            for (size_t c = 0; c < 3; ++c) {
                const size_t i = (size_t(y) * kWidth + size_t(x)) * 3 + c;
                const double d = 255.0 * (srgbEncode(images[1][i]) - srgbEncode(images[0][i]));
                squared += d * d;
                ++count;
            }
    const double psnr = 10.0 * std::log10(255.0 * 255.0 / std::max(squared / double(count), 1e-12));
    EXPECT_GE(psnr, 35.0);
    std::printf("BC1 ramp render PSNR %.1f dB\n", psnr);
}

TEST_F(TextureTest, CompressedTexturesComeBackFromTheDiskCache) {
    // Once a texture's blocks are encoded they are read from the disk cache (the tests' folder in
    // the build tree) by the file's content: a second load after the first was released, and a
    // copy of the file under another name, encode nothing.
    setCompression(true);
    const std::string file = writePng("cached.png", 8, [](int x, int y) {
        return Rgb8{uint8_t(30 * x), uint8_t(30 * y), uint8_t(getpid() % 251)};
    });
    const std::string copy = (dir_ / "copy.png").string();
    std::filesystem::copy_file(file, copy);
    for (const std::string& f : {file, file, copy}) {
        host.addPrim("material", "/Looks/M", textured("diffuseColor", f));
        addPlane("/Plane", "/Looks/M");
        render();
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Plane"), OBSCURA_OK);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Looks/M"), OBSCURA_OK);
    }
    auto loads = [&](const std::string& f, const char* how) {
        return std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(), [&](const std::string& m) {
            return m.rfind("loaded texture " + f + " (8x8 BC1 sRGB,", 0) == 0 && m.find(how) != std::string::npos;
        });
    };
    EXPECT_EQ(loads(file, "from the disk cache") + loads(file, "compressed on the CPU"), 2);
    EXPECT_GE(loads(file, "from the disk cache"), 1);
    EXPECT_EQ(loads(copy, "from the disk cache"), 1);
}

TEST_F(TextureTest, CompressedTexturesFromTheDiskCacheRenderAsTheyDidWhenEncoded) {
    // A compressed material texture's second load is made from the disk cache alone (the blocks
    // and a summary of the file: formats, size, mean), without decoding the file: the same image
    // as the first load's, bit for bit, for an opaque (BC1) and a cut-out (BC3) texture. As
    // emission its mean also sets the accumulation's pre-exposure. One sample a pixel, no
    // temporal change.
    setCompression(true);
    setBool(host, "taa", false);
    setBool(host, "ssao", false);
    for (const bool opaque : {true, false}) {
        // Texels no earlier run has encoded (blue from the bytes of a random number), so that the
        // first load encodes; the cut-out's right half has alpha 40.
        const uint32_t seed = std::random_device{}();
        std::vector<uint8_t> rgba;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (int v : {16 * x, 16 * y, int((x * y + (seed >> (8 * ((x + y) % 4)))) % 256), opaque || x < 8 ? 255 : 40})
                    rgba.push_back(uint8_t(v));
        const std::string file = (dir_ / (opaque ? "opaque.png" : "cutout.png")).string();
        ASSERT_FALSE(image::isError(image::writePng(file, 16, 16, image::PngFormat::Rgba, rgba.data(), 16 * 4)));
        std::vector<std::vector<float>> images;
        for (int load = 0; load < 2; ++load) {
            auto values = textured("emissiveColor", file);
            values["inputs:diffuseColor"] = HostValue::float3(0.2f, 0.2f, 0.2f);
            host.addPrim("material", "/Looks/Glow", values);
            addPlane("/Plane", "/Looks/Glow");
            render();
            images.push_back(color);
            ASSERT_EQ(host.api().removePrim(host.delegate(), "/Plane"), OBSCURA_OK);
            ASSERT_EQ(host.api().removePrim(host.delegate(), "/Looks/Glow"), OBSCURA_OK);
        }
        const std::string format = opaque ? "BC1 sRGB" : "BC3 sRGB";
        auto loads = [&](const char* how) {
            return std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(), [&](const std::string& m) {
                return m.rfind("loaded texture " + file + " (16x16 " + format + ",", 0) == 0 &&
                       m.find(how) != std::string::npos;
            });
        };
        EXPECT_EQ(loads("compressed on the CPU"), 1) << format;
        EXPECT_EQ(loads("from the disk cache"), 1) << format;
        ASSERT_EQ(images[0].size(), images[1].size());
        size_t differing = 0;
        for (size_t i = 0; i < images[0].size(); ++i) differing += images[0][i] != images[1][i] ? 1 : 0;
        EXPECT_EQ(differing, 0u) << format;
        EXPECT_NE(*std::min_element(images[0].begin(), images[0].end()),
                  *std::max_element(images[0].begin(), images[0].end()));
    }
}

TEST_F(TextureTest, DamagedTextureSummariesInTheDiskCacheAreMisses) {
    // A colour texture's summary in the disk cache (formats, size, mean) overwritten with bytes
    // naming no format: the next load decodes the file again, finds its blocks, and renders as the
    // first did; no unknown format reaches the device (validation would fail the test).
    // The folder the plugin chose (delegate/cache_folder.h's order).
    std::filesystem::path folder;
    if (const char* set = std::getenv("OBSCURA_TEXTURE_CACHE"); set && *set) folder = set;
    else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) folder = std::filesystem::path(xdg) / "obscura";
    else if (const char* home = std::getenv("HOME"); home && *home) folder = std::filesystem::path(home) / ".cache" / "obscura";
    ASSERT_FALSE(folder.empty() || folder == "off") << "the texture disk cache is off";
    const auto started = std::filesystem::file_time_type::clock::now() - std::chrono::seconds(2);
    setCompression(true);
    setBool(host, "taa", false);
    setBool(host, "ssao", false);
    const uint32_t seed = std::random_device{}();
    const std::string file = writePng("damaged.png", 16, [seed](int x, int y) {
        return Rgb8{uint8_t(16 * x), uint8_t(16 * y), uint8_t((3 * x + y + (seed >> (8 * ((x + y) % 4)))) % 256)};
    });
    std::vector<std::vector<float>> images;
    for (int load = 0; load < 2; ++load) {
        host.addPrim("material", "/Looks/M", textured("diffuseColor", file));
        addPlane("/Plane", "/Looks/M");
        render();
        images.push_back(color);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Plane"), OBSCURA_OK);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Looks/M"), OBSCURA_OK);
        // The summaries written since the test began: this load's (and any a test beside it wrote,
        // whose next load then decodes once more).
        if (load == 0)
            for (const auto& entry : std::filesystem::directory_iterator(folder))
                if (entry.path().filename().string().rfind("colour-summary-", 0) == 0 &&
                    entry.last_write_time() >= started) {
                    std::FILE* f = std::fopen(entry.path().c_str(), "r+b");
                    ASSERT_NE(f, nullptr);
                    const std::vector<unsigned char> garbage(32, 0xff);
                    std::fwrite(garbage.data(), 1, garbage.size(), f);
                    std::fclose(f);
                }
    }
    EXPECT_EQ(images[0], images[1]);
    EXPECT_EQ(loadsOf(file), 2u);
}

TEST_F(TextureTest, EncodedNormalMapsComeBackFromTheDiskCacheAsTheyWereEncoded) {
    // A BC5 normal map's blocks come back from the disk cache by the file's content (the file's
    // header alone read, its texels neither decoded nor filtered): the second load, after the
    // first was released, renders exactly what the first did. Bumps of every direction, lit from
    // the side, so each texel's normal shows; one sample a pixel, no temporal change.
    setCompression(true);
    setBool(host, "taa", false);
    setBool(host, "ssao", false);
    // Each texel's z one code lower where a bit of a random number says so: a map no earlier run
    // has encoded.
    const uint32_t seed = std::random_device{}();
    const std::string file = writePng("bumps.png", 16, [seed](int x, int y) {
        const double a = 0.4 * x + 0.9 * y, tilt = 0.05 * ((x * 7 + y * 3) % 11);
        auto code = [](double v) { return uint8_t(std::lround((0.5 * v + 0.5) * 255.0)); };
        return Rgb8{code(std::sin(tilt) * std::cos(a)), code(std::sin(tilt) * std::sin(a)),
                    uint8_t(code(std::cos(tilt)) - ((seed >> ((16 * y + x) % 32)) & 1u))};
    });
    host.addPrim("distantLight", "/Sun", {{"inputs:intensity", HostValue::floatValue(1.0f)}},
                 lightPointingAlong({-0.6, 0.0, -0.8}));
    std::vector<std::vector<float>> images;
    for (int load = 0; load < 2; ++load) {
        host.addPrim("material", "/Looks/Bumped", textured("normal", file, {{"sourceColorSpace", HostValue::token("raw")},
                                                                            {"channel", HostValue::token("rgb")},
                                                                            {"scale", float4(2.0f, 2.0f, 2.0f, 1.0f)},
                                                                            {"bias", float4(-1.0f, -1.0f, -1.0f, 0.0f)}}));
        addPlane("/Plane", "/Looks/Bumped");
        render();
        images.push_back(color);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Plane"), OBSCURA_OK);
        ASSERT_EQ(host.api().removePrim(host.delegate(), "/Looks/Bumped"), OBSCURA_OK);
    }
    auto loads = [&](const char* how) {
        return std::count_if(host.loggedInfos().begin(), host.loggedInfos().end(), [&](const std::string& m) {
            return m.rfind("loaded texture " + file + " (16x16 BC5,", 0) == 0 && m.find(how) != std::string::npos;
        });
    };
    EXPECT_EQ(loads("encoded on the CPU"), 1);
    EXPECT_EQ(loads("from the disk cache"), 1);
    ASSERT_EQ(images[0].size(), images[1].size());
    size_t differing = 0;
    for (size_t i = 0; i < images[0].size(); ++i) differing += images[0][i] != images[1][i] ? 1 : 0;
    EXPECT_EQ(differing, 0u);
    // Not a flat image: the bumps shade the plane.
    EXPECT_NE(*std::min_element(images[0].begin(), images[0].end()), *std::max_element(images[0].begin(), images[0].end()));
}

TEST_F(TextureTest, MinifiedTextureIntegratesItsReconstruction) {
    // A one-texel black and white checker, 256 texels over 64 pixels: each pixel's footprint
    // covers 4x4 texels. What a path tracer integrates there is the texture's reconstruction,
    // bilinear in the bytes and decoded after (as the magnified texels blend): over a period,
    // integrated here at 64 x 64 points a texel, 0.246. The mean of the decoded texels would give
    // 0.5, that of the bytes 0.216. Mip 2 holds these means; one real-time frame, without temporal
    // AA, reads it (a still's frames each look up a finer mip, their share of the pixel). Allowed:
    // the mips' 4 x 4-point quadrature (0.0038 here, TextureMips) and an 8-bit step at 0.25 (0.004).
    setNumber("taa", 0.0);
    std::string file = writePng("fine.png", 256, [](int x, int y) {
        return (x + y) % 2 ? Rgb8{255, 255, 255} : Rgb8{0, 0, 0};
    });
    constexpr int kPoints = 64;
    double integral = 0.0;
    for (int j = 0; j < 2 * kPoints; ++j)
        for (int i = 0; i < 2 * kPoints; ++i) {
            // From texel (0, 0)'s centre: the bilinear weights of the white texels (1, 0), (0, 1).
            const double u = (i + 0.5) / kPoints - 0.5, v = (j + 0.5) / kPoints - 0.5;
            const double fu = u - std::floor(u), fv = v - std::floor(v);
            const bool whiteFirst = (int(std::floor(u)) + int(std::floor(v))) % 2 != 0;
            const double white = fu * (1 - fv) + (1 - fu) * fv;
            integral += srgbDecode(whiteFirst ? 1.0 - white : white);
        }
    integral /= 4.0 * kPoints * kPoints;
    host.addPrim("material", "/Looks/M", textured("diffuseColor", file));
    addPlane("/Plane", "/Looks/M");
    render();
    std::printf("[ metric ] one-texel checker minified 4x: reconstruction's integral %.4f, rendered %.4f\n", integral,
                albedo[(size_t(12) * kWidth + 20) * 3]);
    for (int y : {12, 40})
        for (int x : {20, 50})
            for (size_t c = 0; c < 3; ++c)
                EXPECT_NEAR(albedo[(size_t(y) * kWidth + size_t(x)) * 3 + c], integral, 0.01f);
    EXPECT_EQ(loadsOf(file), 1u);
}

// A checker of 44-texel squares on a 512-texel map over the 64 pixels: 8 texels a pixel, so its
// edges fall 5.5 pixels apart, half of them across pixels. Lit by a white dome (diffuse only, no
// SSAO), the pixel's integral is its box integral of the reconstructed albedo: bilinear in the
// file's sRGB-encoded values, decoded after (delegate/texture_cache.cpp), as Cycles reconstructs
// 8-bit textures.
class MinifiedChecker : public TextureTest {
protected:
    static constexpr int kTexels = 512;
    static Rgb8 texel(int x, int y) { return (x / 44 + y / 44) % 2 ? Rgb8{230, 230, 230} : Rgb8{30, 30, 30}; }

    MinifiedChecker() {
        std::string file = writePng("checker.png", kTexels, texel);
        // Clamped, so that the border pixels' lookups do not wrap around to the far side's squares.
        host.addPrim("material", "/Looks/M",
                     textured("diffuseColor", file,
                              {{"wrapS", HostValue::token("clamp")}, {"wrapT", HostValue::token("clamp")}}));
        addPlane("/Plane", "/Looks/M");
        host.addPrim("domeLight", "/Sky",
                     {{"inputs:intensity", HostValue::floatValue(1.0f)}, {"inputs:specular", HostValue::floatValue(0.0f)}});
        setNumber("ssao", 0.0);
    }
    // PSNR (peak 1) of the rendered colour against each pixel's integral, scaled by the dome's
    // irradiance over pi as seen in the middle of a bright square (no edge within 2 pixels). The
    // integral is numerical: the midpoints of kSteps x kSteps cells a texel, whose edges hold the
    // reconstruction's kinks at the texel centres.
    double psnrAgainstThePixelIntegral() const {
        constexpr int kSteps = 8, kAcross = 8 * kSteps;  // points along a pixel's side
        const float lightScale = colorAt(8, 2)[0] / srgb8Exact(texel(68, 20)[0]);
        // Along one axis of pixel p: each point's two texels (clamped at the map's border) and the
        // second one's bilinear weight.
        struct Tap {
            int first, second;
            double weight;
        };
        auto taps = [&](int p) {
            std::vector<Tap> out;
            for (int i = 0; i < kAcross; ++i) {
                const double at = 8.0 * p + (i + 0.5) / kSteps - 0.5;  // from the first texel's centre
                const int first = int(std::floor(at));
                out.push_back({std::clamp(first, 0, kTexels - 1), std::clamp(first + 1, 0, kTexels - 1), at - first});
            }
            return out;
        };
        double squaredError = 0.0;
        for (int y = 0; y < kHeight; ++y) {
            const std::vector<Tap> rows = taps(y);
            for (int x = 0; x < kWidth; ++x) {
                const std::vector<Tap> columns = taps(x);
                double integral = 0.0;
                for (const Tap& r : rows)
                    for (const Tap& c : columns) {
                        const double top = (1.0 - c.weight) * texel(c.first, r.first)[0] + c.weight * texel(c.second, r.first)[0];
                        const double bottom =
                            (1.0 - c.weight) * texel(c.first, r.second)[0] + c.weight * texel(c.second, r.second)[0];
                        integral += srgbDecode(((1.0 - r.weight) * top + r.weight * bottom) / 255.0);
                    }
                double error = colorAt(x, y)[0] - lightScale * integral / (kAcross * kAcross);
                squaredError += error * error;
            }
        }
        return 10.0 * std::log10(1.0 / (squaredError / (kWidth * kHeight)));
    }
};

TEST_F(MinifiedChecker, StillConvergesToThePixelIntegral) {
    // Lookups filtered over a whole pixel's mip footprint in each of the still's frames blur the
    // pixel's box by a pixel more, each edge spreading into the pixels beside it (24.6 dB). Enough
    // frames that the samples' own estimate of an edge's coverage is within the bar (16 leave 1/16
    // steps, about 33 dB here), their mean kept in 32-bit floats (passes/temporal_aa.h): what is
    // left is how each frame's lookups filter.
    constexpr int kStillFrames = 256;
    setNumber("taa:frames", kStillFrames);
    render();
    for (int frame = 0; frame < kStillFrames + 2 && !renderStats(host).converged; ++frame) render();
    ASSERT_TRUE(renderStats(host).converged);
    const double psnr = psnrAgainstThePixelIntegral();
    std::printf("[ metric ] minified checker, still of %d frames vs the pixels' box integral: %.2f dB\n", kStillFrames,
                psnr);
    // The bar of a converged still's edges (EdgeConvergence.MsaaStillIsThePixelIntegral).
    EXPECT_GE(psnr, 45.0);
}

TEST_F(MinifiedChecker, ReferenceIsThePixelIntegral) {
    // The reference resolves four samples a sub-frame over the pixel's box, whichever pixel's
    // fragment drew them: shaded once per pixel at its centre, a texture is seen at the pixel's
    // middle quarter alone along x (the sub-frames' x jitter spans a quarter pixel, the sample
    // pattern the rest), so each sample is shaded at its own position.
    setNumber("reference", 256);
    render();
    const double psnr = psnrAgainstThePixelIntegral();
    std::printf("[ metric ] minified checker, reference of 256 sub-frames vs the pixels' box integral: %.2f dB\n",
                psnr);
    EXPECT_GE(psnr, 45.0);
}

TEST_F(TextureTest, SubdividedMeshesKeepTheirTextureCoordinates) {
    std::string file = writeBlocks("blocks.png");
    host.addPrim("material", "/Looks/M", textured("diffuseColor", file));
    HostValue level;
    level.type = OBSCURA_VALUE_INT;
    level.ints = {2};
    addPlane("/Plane", "/Looks/M", 1.0f, 0.0, kHalf,
             {{"subdivisionScheme", HostValue::token("catmullClark")}, {"obscura:refineLevel", level}});
    host.setInterpolation("/Plane", "primvars:st", OBSCURA_INTERPOLATION_FACE_VARYING);
    render();
    // The refined quad keeps its sharp corners and straight boundary: each block stays in its
    // quadrant (checked away from the borders, where refinement may shift st slightly).
    expectAlbedo(14, 14, decoded(kBlocks[0]), "top left");
    expectAlbedo(50, 14, decoded(kBlocks[1]), "top right");
    expectAlbedo(14, 50, decoded(kBlocks[2]), "bottom left");
    expectAlbedo(50, 50, decoded(kBlocks[3]), "bottom right");
}

}  // namespace
}  // namespace obscura::test
