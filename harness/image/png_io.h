// PNG writing through libpng, and reading of PNG, JPEG, TGA, BMP, HDR ... through stb_image.
//
// Reading does no colour conversion: display-referred files (PNG, JPEG) are compared as stored,
// 8-bit values v become v / 255 and 16-bit values v / 65535. Radiance .hdr files read as their
// linear float values. Grey images become R = G = B; the alpha channel A is kept when present.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "harness/image/image.h"

namespace obscura::image {

enum class PngFormat { Rgb, Rgba };

// Writes 8-bit pixels (3 or 4 bytes each, rows top first, `rowStrideBytes` apart) as a PNG.
Status writePng(const std::string& path, int width, int height, PngFormat format,
                const uint8_t* data, size_t rowStrideBytes);

// Writes 16-bit RGB pixels (3 values each, rows top first, tightly packed) as a 16-bit PNG,
// values unchanged (libpng's simplified API marks 16-bit files gamma 1.0; readers of texture
// files take the values as sourceColorSpace says).
Status writePng16(const std::string& path, int width, int height, const uint16_t* rgb);

// Writes the R, G, B (and A, when present) channels of `image` as an 8-bit PNG: values are
// clamped to [0,1] and rounded, with no transfer function applied (the image is taken to be
// display-referred already, like makeDiffImage's output). NaN is written as 0.
Status writePng(const std::string& path, const Image& image);

// Reads any format stb_image knows into an image with channels R, G, B[, A].
Result<Image> readStbImage(const std::string& path);

}  // namespace obscura::image
