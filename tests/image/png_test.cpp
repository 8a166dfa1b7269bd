// PNG writing through libpng and reading through stb_image.
#include <png.h>
#include <stb_image_write.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "harness/image/png_io.h"
#include "tests/image/temp_files.h"

namespace obscura::image {
namespace {

class PngTest : public testing::TempFiles {};

Image readOk(const std::string& file) {
    Result<Image> r = readStbImage(file);
    EXPECT_FALSE(isError(r)) << errorOf(r);
    return isError(r) ? Image{} : std::get<Image>(r);
}

// Every byte value appears, with a row stride longer than a row.
void roundTrip(const std::string& file, PngFormat format, int channelCount) {
    constexpr int kW = 13;
    constexpr int kH = 21;
    const size_t stride = kW * static_cast<size_t>(channelCount) + 5;
    std::vector<uint8_t> bytes(stride * kH, 0xAB);
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW * channelCount; ++x) {
            bytes[static_cast<size_t>(y) * stride + x] = static_cast<uint8_t>(y * 97 + x * 31);
        }
    }
    const Status written = writePng(file, kW, kH, format, bytes.data(), stride);
    ASSERT_FALSE(isError(written)) << errorOf(written);

    const Image image = readOk(file);
    ASSERT_EQ(image.width, kW);
    ASSERT_EQ(image.height, kH);
    ASSERT_EQ(image.channelCount(), static_cast<size_t>(channelCount));
    EXPECT_EQ(image.channels[0], "R");
    EXPECT_EQ(image.channels.back(), channelCount == 4 ? "A" : "B");
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            for (int c = 0; c < channelCount; ++c) {
                const uint8_t expected = bytes[static_cast<size_t>(y) * stride +
                                               static_cast<size_t>(x * channelCount + c)];
                EXPECT_EQ(image.at(x, y, c), static_cast<float>(expected) / 255.0f);
            }
        }
    }
}

TEST_F(PngTest, RgbaRoundTripIsExact) { roundTrip(path("rgba.png"), PngFormat::Rgba, 4); }

TEST_F(PngTest, RgbRoundTripIsExact) { roundTrip(path("rgb.png"), PngFormat::Rgb, 3); }

TEST_F(PngTest, WritingAnImageClampsAndRounds) {
    Image image = Image::make(3, 1, {"R", "G", "B", "A"});
    image.pixels = {-1.0f, 0.0f, 0.5f, 1.0f,                                  //
                    2.0f, 0.25f, 1.0f / 255.0f, 0.499f / 255.0f,              //
                    std::numeric_limits<float>::quiet_NaN(), 0.75f, 0.2f, 0.8f};
    ASSERT_FALSE(isError(writePng(path("img.png"), image)));
    const Image back = readOk(path("img.png"));
    const std::vector<int> expected = {0, 0, 128, 255, 255, 64, 1, 0, 0, 191, 51, 204};
    ASSERT_EQ(back.pixels.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(back.pixels[i], static_cast<float>(expected[i]) / 255.0f) << i;
    }
}

TEST_F(PngTest, WritingAnImageWithoutColourIsAnError) {
    const Image depth = Image::make(2, 2, {"Z"});
    EXPECT_TRUE(isError(writePng(path("z.png"), depth)));
}

TEST_F(PngTest, WriteErrorsNameTheFile) {
    const uint8_t pixel[4] = {1, 2, 3, 4};
    const std::string file = path("no/such/dir/x.png");
    const Status s = writePng(file, 1, 1, PngFormat::Rgba, pixel, 4);
    ASSERT_TRUE(isError(s));
    EXPECT_NE(errorOf(s).find(file), std::string::npos) << errorOf(s);
    EXPECT_TRUE(isError(writePng(path("short.png"), 2, 1, PngFormat::Rgba, pixel, 4)));
    EXPECT_TRUE(isError(writePng(path("null.png"), 1, 1, PngFormat::Rgb, nullptr, 3)));
}

TEST_F(PngTest, GreyBecomesRgb) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = 2;
    png.height = 1;
    png.format = PNG_FORMAT_GA;
    const uint8_t ga[4] = {10, 255, 200, 100};
    ASSERT_NE(png_image_write_to_file(&png, path("grey.png").c_str(), 0, ga, 0, nullptr), 0);
    const Image image = readOk(path("grey.png"));
    EXPECT_EQ(image.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_EQ(image.pixels, (std::vector<float>{10 / 255.0f, 10 / 255.0f, 10 / 255.0f, 1.0f,
                                                200 / 255.0f, 200 / 255.0f, 200 / 255.0f,
                                                100 / 255.0f}));
}

TEST_F(PngTest, SixteenBitKeepsItsPrecision) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = 1;
    png.height = 1;
    png.format = PNG_FORMAT_LINEAR_RGB;  // 16 bits per channel
    const uint16_t rgb[3] = {0, 32768, 65535};
    ASSERT_NE(png_image_write_to_file(&png, path("deep.png").c_str(), 0, rgb, 0, nullptr), 0);
    const Image image = readOk(path("deep.png"));
    EXPECT_EQ(image.pixels, (std::vector<float>{0.0f, 32768 / 65535.0f, 1.0f}));
}

TEST_F(PngTest, ReadsJpeg) {
    std::vector<uint8_t> rgb(16 * 16 * 3);
    for (size_t i = 0; i < rgb.size(); i += 3) {
        rgb[i] = 200;
        rgb[i + 1] = 100;
        rgb[i + 2] = 50;
    }
    ASSERT_NE(stbi_write_jpg(path("flat.jpg").c_str(), 16, 16, 3, rgb.data(), 100), 0);
    const Image image = readOk(path("flat.jpg"));
    ASSERT_EQ(image.channelCount(), 3u);
    EXPECT_NEAR(image.at(8, 8, 0), 200 / 255.0f, 3 / 255.0f);
    EXPECT_NEAR(image.at(8, 8, 1), 100 / 255.0f, 3 / 255.0f);
    EXPECT_NEAR(image.at(8, 8, 2), 50 / 255.0f, 3 / 255.0f);
}

TEST_F(PngTest, MissingFileIsAnErrorNamingIt) {
    const std::string file = path("absent.png");
    const Result<Image> r = readStbImage(file);
    ASSERT_TRUE(isError(r));
    EXPECT_NE(errorOf(r).find(file), std::string::npos) << errorOf(r);
}

TEST_F(PngTest, RandomAndTruncatedFilesAreErrors) {
    std::mt19937 rng(4);
    std::vector<char> noise(2048);
    for (char& b : noise) b = static_cast<char>(rng());
    writeBytes(path("noise.png"), noise);
    EXPECT_TRUE(isError(readStbImage(path("noise.png"))));

    const uint8_t pixels[4 * 8 * 8] = {};
    ASSERT_FALSE(isError(writePng(path("full.png"), 8, 8, PngFormat::Rgba, pixels, 32)));
    const std::vector<char> bytes = readBytes(path("full.png"));
    for (size_t keep : {size_t{0}, size_t{8}, size_t{30}, bytes.size() / 2}) {
        const std::string cut = path("cut" + std::to_string(keep) + ".png");
        writeBytes(cut, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(keep)));
        EXPECT_TRUE(isError(readStbImage(cut))) << "kept " << keep << " of " << bytes.size();
    }
}

}  // namespace
}  // namespace obscura::image
