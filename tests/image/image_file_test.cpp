// readImage picks the reader by extension.
#include <gtest/gtest.h>

#include <filesystem>

#include "harness/image/exr_writer.h"
#include "harness/image/image_file.h"
#include "harness/image/png_io.h"
#include "tests/image/temp_files.h"

namespace obscura::image {
namespace {

class ImageFileTest : public testing::TempFiles {};

TEST_F(ImageFileTest, ExrExtensionInAnyCaseReadsOpenExr) {
    const float z[2] = {1.5f, -2.0f};
    const std::vector<ExrLayer> layers = {
        {"depth", {"Z"}, ExrLayer::PixelType::Float, z, 2 * sizeof(float)}};
    for (const char* name : {"a.exr", "b.EXR"}) {
        ASSERT_FALSE(isError(writeExr(path(name), 2, 1, layers)));
        const Result<Image> r = readImage(path(name));
        ASSERT_FALSE(isError(r)) << errorOf(r);
        EXPECT_EQ(std::get<Image>(r).channels, std::vector<std::string>{"Z"});
        EXPECT_EQ(std::get<Image>(r).pixels, (std::vector<float>{1.5f, -2.0f}));
    }
}

TEST_F(ImageFileTest, OtherExtensionsReadThroughStb) {
    const uint8_t rgb[3] = {0, 51, 255};
    ASSERT_FALSE(isError(writePng(path("a.png"), 1, 1, PngFormat::Rgb, rgb, 3)));
    const Result<Image> r = readImage(path("a.png"));
    ASSERT_FALSE(isError(r)) << errorOf(r);
    EXPECT_EQ(std::get<Image>(r).pixels, (std::vector<float>{0.0f, 0.2f, 1.0f}));

    // A PNG named .exr goes to OpenEXR, which refuses it.
    std::filesystem::copy_file(path("a.png"), path("png.exr"));
    EXPECT_TRUE(isError(readImage(path("png.exr"))));
}

TEST_F(ImageFileTest, MissingFilesAreErrorsNamingThem) {
    for (const char* name : {"absent.exr", "absent.png", "absent"}) {
        const Result<Image> r = readImage(path(name));
        ASSERT_TRUE(isError(r)) << name;
        EXPECT_NE(errorOf(r).find(path(name)), std::string::npos) << errorOf(r);
    }
}

}  // namespace
}  // namespace obscura::image
