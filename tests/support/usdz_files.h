// USDZ packages written by tests, with libzip, and files read back whole.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace obscura::test {

using PackageFiles = std::vector<std::pair<std::string, std::string>>;  // (name, contents), in order

// `files` as an uncompressed zip at `archive` (folders made as needed), in this order: the first
// layer file is the package's root layer. "" when written, else the reason.
std::string writeUsdz(const std::filesystem::path& archive, const PackageFiles& files);

// A file's bytes; "" when it cannot be read.
std::string fileBytes(const std::filesystem::path& file);

}  // namespace obscura::test
