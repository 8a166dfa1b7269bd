// EXR writing and reading: channel layout, exact values, and failures that must not crash.
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>

#include "harness/image/exr_reader.h"
#include "harness/image/exr_writer.h"
#include "tests/image/temp_files.h"

namespace obscura::image {
namespace {

// A small frame with every kind of AOV the renderer writes.
struct Frame {
    static constexpr int kWidth = 7;
    static constexpr int kHeight = 5;
    static constexpr size_t kPixels = kWidth * kHeight;
    std::vector<float> rgba = std::vector<float>(kPixels * 4);
    std::vector<float> depth = std::vector<float>(kPixels);
    std::vector<float> normal = std::vector<float>(kPixels * 3);
    std::vector<int32_t> primId = std::vector<int32_t>(kPixels);

    Frame() {
        for (size_t i = 0; i < kPixels; ++i) {
            const float f = static_cast<float>(i);
            // HDR colour, including values half cannot hold exactly and a negative one.
            rgba[i * 4 + 0] = 0.1f * f + 0.0123f;
            rgba[i * 4 + 1] = f * f * 3.7f;
            rgba[i * 4 + 2] = -0.25f + 0.01f * f;
            rgba[i * 4 + 3] = 1.0f / (1.0f + f);
            depth[i] = i % 6 == 0 ? std::numeric_limits<float>::infinity() : 0.5f + 1.3f * f;
            normal[i * 3 + 0] = std::sin(f);
            normal[i * 3 + 1] = std::cos(f);
            normal[i * 3 + 2] = -0.333333f * f;
            primId[i] = i % 4 == 0 ? -1 : static_cast<int32_t>(i * 1000 + 7);
        }
    }

    std::vector<ExrLayer> layers() const {
        using T = ExrLayer::PixelType;
        return {
            {"", {"R", "G", "B", "A"}, T::Half, rgba.data(), kWidth * 4 * sizeof(float)},
            {"depth", {"Z"}, T::Float, depth.data(), kWidth * sizeof(float)},
            {"normal", {"X", "Y", "Z"}, T::Float, normal.data(), kWidth * 3 * sizeof(float)},
            {"primId", {"id"}, T::Uint, primId.data(), kWidth * sizeof(int32_t)},
        };
    }
};

class ExrTest : public testing::TempFiles {};

Image readOk(const std::string& file) {
    Result<Image> r = readExr(file);
    EXPECT_FALSE(isError(r)) << errorOf(r);
    return isError(r) ? Image{} : std::get<Image>(r);
}

TEST(ExrChannelName, FollowsCompositorConventions) {
    EXPECT_EQ(exrChannelName("", "R"), "R");
    EXPECT_EQ(exrChannelName("depth", "Z"), "Z");
    EXPECT_EQ(exrChannelName("depth", "W"), "depth.W");
    EXPECT_EQ(exrChannelName("position", "Z"), "position.Z");
    EXPECT_EQ(exrChannelName("normal", "X"), "normal.X");
    EXPECT_EQ(exrChannelName("primId", "id"), "primId.id");
}

TEST_F(ExrTest, RoundTripKeepsEveryLayer) {
    const Frame frame;
    const std::string file = path("frame.exr");
    const Status written = writeExr(file, Frame::kWidth, Frame::kHeight, frame.layers());
    ASSERT_FALSE(isError(written)) << errorOf(written);

    const Image image = readOk(file);
    ASSERT_EQ(image.width, Frame::kWidth);
    ASSERT_EQ(image.height, Frame::kHeight);
    EXPECT_EQ(image.channels, (std::vector<std::string>{"R", "G", "B", "A", "Z", "normal.X",
                                                        "normal.Y", "normal.Z", "primId.id"}));
    for (int y = 0; y < Frame::kHeight; ++y) {
        for (int x = 0; x < Frame::kWidth; ++x) {
            const size_t i = static_cast<size_t>(y * Frame::kWidth + x);
            for (int c = 0; c < 4; ++c) {
                const float written4 = frame.rgba[i * 4 + static_cast<size_t>(c)];
                // Exactly the half nearest to the value, which is within half's precision.
                EXPECT_EQ(image.at(x, y, c), static_cast<float>(half(written4)));
                EXPECT_NEAR(image.at(x, y, c), written4, std::abs(written4) * 0x1p-11f);
            }
            EXPECT_EQ(image.at(x, y, image.channelIndex("Z")), frame.depth[i]);
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(image.at(x, y, image.channelIndex("normal.X") + c),
                          frame.normal[i * 3 + static_cast<size_t>(c)]);
            }
            EXPECT_EQ(image.at(x, y, image.channelIndex("primId.id")),
                      static_cast<float>(frame.primId[i]));
        }
    }
}

TEST_F(ExrTest, HeaderHasNamedTypedChannelsAndLinearRec709) {
    const Frame frame;
    const std::string file = path("frame.exr");
    ASSERT_FALSE(isError(writeExr(file, Frame::kWidth, Frame::kHeight, frame.layers())));

    Imf::InputFile in(file.c_str());
    const Imf::Header& header = in.header();
    std::map<std::string, Imf::PixelType> channels;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
        channels[it.name()] = it.channel().type;
    }
    const std::map<std::string, Imf::PixelType> expected = {
        {"R", Imf::HALF},         {"G", Imf::HALF},         {"B", Imf::HALF},
        {"A", Imf::HALF},         {"Z", Imf::FLOAT},        {"normal.X", Imf::FLOAT},
        {"normal.Y", Imf::FLOAT}, {"normal.Z", Imf::FLOAT}, {"primId.id", Imf::UINT},
    };
    EXPECT_EQ(channels, expected);
    EXPECT_EQ(header.compression(), Imf::ZIP_COMPRESSION);
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(Frame::kWidth - 1, Frame::kHeight - 1));
    EXPECT_EQ(header.dataWindow(), window);
    EXPECT_EQ(header.displayWindow(), window);
    ASSERT_TRUE(Imf::hasChromaticities(header));
    const Imf::Chromaticities& chroma = Imf::chromaticities(header);
    EXPECT_EQ(chroma.red, Imath::V2f(0.64f, 0.33f));
    EXPECT_EQ(chroma.green, Imath::V2f(0.30f, 0.60f));
    EXPECT_EQ(chroma.blue, Imath::V2f(0.15f, 0.06f));
    EXPECT_EQ(chroma.white, Imath::V2f(0.3127f, 0.3290f));

    // The UINT channel holds the int32 bit pattern: -1 is 0xFFFFFFFF.
    std::vector<uint32_t> ids(Frame::kPixels);
    Imf::FrameBuffer fb;
    fb.insert("primId.id", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(ids.data()),
                                      sizeof(uint32_t), sizeof(uint32_t) * Frame::kWidth));
    in.setFrameBuffer(fb);
    in.readPixels(0, Frame::kHeight - 1);
    EXPECT_EQ(ids[0], 0xFFFFFFFFu);
    EXPECT_EQ(ids[1], 1007u);
}

TEST_F(ExrTest, EveryCompressionRoundTrips) {
    const Frame frame;
    const std::map<ExrCompression, Imf::Compression> compressions = {
        {ExrCompression::None, Imf::NO_COMPRESSION}, {ExrCompression::Zip, Imf::ZIP_COMPRESSION},
        {ExrCompression::Zips, Imf::ZIPS_COMPRESSION}, {ExrCompression::Piz, Imf::PIZ_COMPRESSION},
        {ExrCompression::Rle, Imf::RLE_COMPRESSION}};
    for (const auto& [ours, theirs] : compressions) {
        const std::string file = path("c" + std::to_string(static_cast<int>(ours)) + ".exr");
        ASSERT_FALSE(isError(writeExr(file, Frame::kWidth, Frame::kHeight, frame.layers(), ours)));
        EXPECT_EQ(Imf::InputFile(file.c_str()).header().compression(), theirs);
        const Image image = readOk(file);
        ASSERT_EQ(image.pixels.size(), Frame::kPixels * 9);
        for (size_t i = 0; i < Frame::kPixels; ++i) {
            EXPECT_EQ(image.pixels[i * 9 + 4], frame.depth[i]);
            EXPECT_EQ(image.pixels[i * 9 + 8], static_cast<float>(frame.primId[i]));
        }
    }
}

TEST_F(ExrTest, RowStrideSkipsPadding) {
    constexpr int kW = 3;
    constexpr int kH = 2;
    constexpr size_t kRowFloats = 8;  // 3 values used, 5 of NaN padding
    std::vector<float> data(kRowFloats * kH, std::numeric_limits<float>::quiet_NaN());
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            data[static_cast<size_t>(y) * kRowFloats + x] = static_cast<float>(y * 10 + x);
        }
    }
    const std::string file = path("stride.exr");
    const std::vector<ExrLayer> layers = {
        {"mask", {"v"}, ExrLayer::PixelType::Float, data.data(), kRowFloats * sizeof(float)}};
    ASSERT_FALSE(isError(writeExr(file, kW, kH, layers)));
    const Image image = readOk(file);
    EXPECT_EQ(image.channels, std::vector<std::string>{"mask.v"});
    EXPECT_EQ(image.pixels, (std::vector<float>{0, 1, 2, 10, 11, 12}));
}

TEST_F(ExrTest, WriterRejectsInvalidLayers) {
    const Frame frame;
    const std::string file = path("bad.exr");
    using T = ExrLayer::PixelType;
    const size_t row = Frame::kWidth * sizeof(float);

    auto expectError = [&](int w, int h, const std::vector<ExrLayer>& layers, const char* what) {
        const Status s = writeExr(file, w, h, layers);
        ASSERT_TRUE(isError(s)) << what;
        EXPECT_NE(errorOf(s).find(file), std::string::npos) << errorOf(s);
    };
    expectError(0, 5, frame.layers(), "zero width");
    expectError(7, 5, {}, "no layers");
    expectError(7, 5, {{"depth", {"Z"}, T::Float, nullptr, row}}, "no data");
    expectError(7, 5, {{"depth", {}, T::Float, frame.depth.data(), row}}, "no channels");
    expectError(7, 5, {{"depth", {"Z"}, T::Float, frame.depth.data(), row - 1}}, "short stride");
    // "depth.Z" and a main-layer "Z" would both be named Z in the file.
    expectError(7, 5,
                {{"depth", {"Z"}, T::Float, frame.depth.data(), row},
                 {"", {"Z"}, T::Float, frame.depth.data(), row}},
                "duplicate channel");
    EXPECT_FALSE(std::filesystem::exists(file));

    const std::string unwritable = path("no/such/dir/x.exr");
    const Status s = writeExr(unwritable, 7, 5, frame.layers());
    ASSERT_TRUE(isError(s));
    EXPECT_NE(errorOf(s).find(unwritable), std::string::npos) << errorOf(s);
}

TEST_F(ExrTest, ReaderUsesTheDataWindow) {
    const std::string file = path("window.exr");
    Imf::Header header(Imath::Box2i({0, 0}, {9, 9}), Imath::Box2i({2, 3}, {5, 7}));
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    std::vector<float> values(4 * 5);
    for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(i);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, values.data(), header.dataWindow()));
    {
        Imf::OutputFile out(file.c_str(), header);
        out.setFrameBuffer(fb);
        out.writePixels(5);
    }
    const Image image = readOk(file);
    EXPECT_EQ(image.width, 4);
    EXPECT_EQ(image.height, 5);
    EXPECT_EQ(image.pixels, values);
}

TEST_F(ExrTest, ReaderTakesTheFirstPartOfAMultiPartFile) {
    const std::string file = path("multi.exr");
    Imf::Header headers[2] = {Imf::Header(2, 2), Imf::Header(2, 2)};
    for (int p = 0; p < 2; ++p) {
        headers[p].setName(p == 0 ? "beauty" : "extra");
        headers[p].setType(Imf::SCANLINEIMAGE);
        headers[p].channels().insert("R", Imf::Channel(Imf::FLOAT));
    }
    {
        Imf::MultiPartOutputFile out(file.c_str(), headers, 2);
        for (int p = 0; p < 2; ++p) {
            std::vector<float> values(4, static_cast<float>(p + 1));
            Imf::FrameBuffer fb;
            fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()),
                                      sizeof(float), 2 * sizeof(float)));
            Imf::OutputPart part(out, p);
            part.setFrameBuffer(fb);
            part.writePixels(2);
        }
    }
    const Image image = readOk(file);
    EXPECT_EQ(image.channels, std::vector<std::string>{"R"});
    EXPECT_EQ(image.pixels, (std::vector<float>{1, 1, 1, 1}));
}

TEST_F(ExrTest, ReaderReadsTiledFiles) {
    const std::string file = path("tiled.exr");
    Imf::Header header(5, 3);
    header.setTileDescription(Imf::TileDescription(2, 2));
    header.channels().insert("G", Imf::Channel(Imf::HALF));
    std::vector<half> values(15);
    for (size_t i = 0; i < values.size(); ++i) values[i] = half(0.5f * static_cast<float>(i));
    Imf::FrameBuffer fb;
    fb.insert("G", Imf::Slice::Make(Imf::HALF, values.data(), header.dataWindow()));
    {
        Imf::TiledOutputFile out(file.c_str(), header);
        out.setFrameBuffer(fb);
        out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
    }
    EXPECT_EQ(readOk(file).pixels, std::vector<float>(values.begin(), values.end()));
}

TEST_F(ExrTest, MissingFileIsAnErrorNamingIt) {
    const std::string file = path("absent.exr");
    const Result<Image> r = readExr(file);
    ASSERT_TRUE(isError(r));
    EXPECT_NE(errorOf(r).find(file), std::string::npos) << errorOf(r);
}

TEST_F(ExrTest, RandomBytesAreAnError) {
    std::mt19937 rng(1);
    std::vector<char> bytes(4096);
    for (char& b : bytes) b = static_cast<char>(rng());
    writeBytes(path("noise.exr"), bytes);
    EXPECT_TRUE(isError(readExr(path("noise.exr"))));

    // The same behind a valid magic number and version, so the header parser sees it.
    const char magic[] = {0x76, 0x2f, 0x31, 0x01, 0x02, 0x00, 0x00, 0x00};
    std::copy(std::begin(magic), std::end(magic), bytes.begin());
    writeBytes(path("noise2.exr"), bytes);
    EXPECT_TRUE(isError(readExr(path("noise2.exr"))));
}

TEST_F(ExrTest, TruncatedFileIsAnError) {
    // Large enough for several ZIP blocks of 16 scanlines.
    constexpr int kSize = 64;
    std::vector<float> rgba(kSize * kSize * 4);
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> dist(0.0f, 4.0f);
    for (float& v : rgba) v = dist(rng);
    const std::string file = path("full.exr");
    ASSERT_FALSE(isError(writeExr(file, kSize, kSize,
                                  {{"", {"R", "G", "B", "A"}, ExrLayer::PixelType::Float,
                                    rgba.data(), kSize * 4 * sizeof(float)}})));
    const std::vector<char> bytes = readBytes(file);
    for (size_t keep : {size_t{0}, size_t{3}, size_t{40}, size_t{300}, bytes.size() / 2,
                        bytes.size() - 1}) {
        const std::string cut = path("cut" + std::to_string(keep) + ".exr");
        writeBytes(cut, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(keep)));
        EXPECT_TRUE(isError(readExr(cut))) << "kept " << keep << " of " << bytes.size();
    }
}

TEST_F(ExrTest, CorruptPixelDataDoesNotCrash) {
    const Frame frame;
    const std::string file = path("frame.exr");
    ASSERT_FALSE(isError(writeExr(file, Frame::kWidth, Frame::kHeight, frame.layers())));
    const std::vector<char> original = readBytes(file);
    std::mt19937 rng(3);
    for (int attempt = 0; attempt < 50; ++attempt) {
        std::vector<char> bytes = original;
        for (int k = 0; k < 8; ++k) bytes[rng() % bytes.size()] = static_cast<char>(rng());
        const std::string corrupt = path("corrupt.exr");
        writeBytes(corrupt, bytes);
        // Either outcome is acceptable; what matters is a result instead of a crash or a throw.
        const Result<Image> r = readExr(corrupt);
        EXPECT_TRUE(isError(r) || !std::get<Image>(r).pixels.empty());
    }
}

}  // namespace
}  // namespace obscura::image
