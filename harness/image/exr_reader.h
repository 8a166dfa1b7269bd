// Reads an OpenEXR file into a float Image: single-part files, and the first part of multi-part
// files; scanline or tiled (the highest-resolution level). Deep files are refused.
//
// All channels become float. HALF and FLOAT channels keep their values. UINT channels are taken
// to hold int32 bit patterns (the convention of exr_writer.h), so 0xFFFFFFFF reads as -1.0f;
// integers beyond 2^24 lose precision in float, which is acceptable for comparing ids.
//
// The image covers the data window; the display window is ignored. Channel order: R, G, B, A
// first when present (in that order), then the others in the file's (alphabetical) order.
#pragma once

#include <string>

#include "harness/image/image.h"

namespace obscura::image {

Result<Image> readExr(const std::string& path);

}  // namespace obscura::image
