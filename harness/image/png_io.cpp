#include "harness/image/png_io.h"

#include <png.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

namespace obscura::image {
namespace {

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

// Copies stb's interleaved samples into an Image, dividing by the format's maximum (255, 65535,
// or 1 for float data). Division rather than multiplication by 1/255 keeps v / 255 exactly the
// float nearest to it, so 8-bit values survive a write/read round trip.
template <class T>
Image toImage(const T* samples, int width, int height, int channelCount, float maxValue) {
    Image image = Image::make(width, height,
                              channelCount == 4 ? std::vector<std::string>{"R", "G", "B", "A"}
                                                : std::vector<std::string>{"R", "G", "B"});
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = static_cast<float>(samples[i]) / maxValue;
    }
    return image;
}

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason != nullptr ? reason : "unknown error";
}

uint8_t quantize(float v) {
    if (!(v > 0.0f)) return 0;  // also NaN
    return static_cast<uint8_t>(std::lround(std::min(v, 1.0f) * 255.0f));
}

}  // namespace

Status writePng(const std::string& path, int width, int height, PngFormat format,
                const uint8_t* data, size_t rowStrideBytes) {
    const size_t channelCount = format == PngFormat::Rgba ? 4 : 3;
    if (width <= 0 || height <= 0) {
        return path + ": invalid size " + std::to_string(width) + "x" + std::to_string(height);
    }
    if (data == nullptr) return path + ": no pixel data";
    if (rowStrideBytes < static_cast<size_t>(width) * channelCount ||
        rowStrideBytes > static_cast<size_t>(std::numeric_limits<png_int_32>::max())) {
        return path + ": invalid row stride " + std::to_string(rowStrideBytes);
    }

    // libpng's simplified API reports errors through png_image::message instead of longjmp,
    // which would skip C++ destructors.
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(width);
    png.height = static_cast<png_uint_32>(height);
    png.format = format == PngFormat::Rgba ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    // Speed over file size: with libpng's default compression writing a 1080p still took 200 ms,
    // a third of the whole `obscura render` on a GPU. The pixels are the same either way.
    png.flags = PNG_IMAGE_FLAG_FAST;
    // For 8-bit data the row stride is counted in bytes.
    if (png_image_write_to_file(&png, path.c_str(), 0, data,
                                static_cast<png_int_32>(rowStrideBytes), nullptr) == 0) {
        return path + ": cannot write PNG: " + png.message;
    }
    return std::monostate{};
}

Status writePng16(const std::string& path, int width, int height, const uint16_t* rgb) {
    if (width <= 0 || height <= 0) {
        return path + ": invalid size " + std::to_string(width) + "x" + std::to_string(height);
    }
    if (rgb == nullptr) return path + ": no pixel data";
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(width);
    png.height = static_cast<png_uint_32>(height);
    // Without alpha, 16-bit ("linear") data is written as it is (with alpha libpng would
    // un-premultiply it).
    png.format = PNG_FORMAT_LINEAR_RGB;
    if (png_image_write_to_file(&png, path.c_str(), 0, rgb, 0, nullptr) == 0) {
        return path + ": cannot write PNG: " + png.message;
    }
    return std::monostate{};
}

Status writePng(const std::string& path, const Image& image) {
    const int r = image.channelIndex("R");
    const int g = image.channelIndex("G");
    const int b = image.channelIndex("B");
    const int a = image.channelIndex("A");
    if (r < 0 || g < 0 || b < 0) return path + ": image has no R, G, B channels to write";

    const bool hasAlpha = a >= 0;
    const size_t channelCount = hasAlpha ? 4 : 3;
    std::vector<uint8_t> bytes(static_cast<size_t>(image.width) *
                               static_cast<size_t>(image.height) * channelCount);
    size_t out = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            bytes[out++] = quantize(image.at(x, y, r));
            bytes[out++] = quantize(image.at(x, y, g));
            bytes[out++] = quantize(image.at(x, y, b));
            if (hasAlpha) bytes[out++] = quantize(image.at(x, y, a));
        }
    }
    return writePng(path, image.width, image.height, hasAlpha ? PngFormat::Rgba : PngFormat::Rgb,
                    bytes.data(), static_cast<size_t>(image.width) * channelCount);
}

Result<Image> readStbImage(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return path + ": no such file";

    int width = 0;
    int height = 0;
    int fileChannels = 0;
    if (stbi_info(path.c_str(), &width, &height, &fileChannels) == 0) {
        return path + ": cannot read image: " + stbReason();
    }
    // Grey (1) and grey+alpha (2) are expanded by stb to RGB and RGBA.
    const int channelCount = (fileChannels == 2 || fileChannels == 4) ? 4 : 3;

    int w = 0;
    int h = 0;
    int n = 0;
    if (stbi_is_hdr(path.c_str()) != 0) {
        std::unique_ptr<float, StbFree> data(stbi_loadf(path.c_str(), &w, &h, &n, channelCount));
        if (data) return toImage(data.get(), w, h, channelCount, 1.0f);
    } else if (stbi_is_16_bit(path.c_str()) != 0) {
        std::unique_ptr<uint16_t, StbFree> data(
            stbi_load_16(path.c_str(), &w, &h, &n, channelCount));
        if (data) return toImage(data.get(), w, h, channelCount, 65535.0f);
    } else {
        std::unique_ptr<uint8_t, StbFree> data(stbi_load(path.c_str(), &w, &h, &n, channelCount));
        if (data) return toImage(data.get(), w, h, channelCount, 255.0f);
    }
    return path + ": cannot read image: " + stbReason();
}

}  // namespace obscura::image
