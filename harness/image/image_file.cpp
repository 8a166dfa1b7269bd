#include "harness/image/image_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "harness/image/exr_reader.h"
#include "harness/image/png_io.h"

namespace obscura::image {

Result<Image> readImage(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".exr" ? readExr(path) : readStbImage(path);
}

}  // namespace obscura::image
