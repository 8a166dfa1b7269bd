// Reading an image of any supported format, chosen by the file extension.
#pragma once

#include <string>

#include "harness/image/image.h"

namespace obscura::image {

// ".exr" (any case) is read by OpenEXR (exr_reader.h), everything else by stb_image (png_io.h).
Result<Image> readImage(const std::string& path);

}  // namespace obscura::image
