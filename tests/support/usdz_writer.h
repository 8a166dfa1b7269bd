// USDZ packages written by tests: zip archives of stored (uncompressed) entries, as the USDZ
// specification asks (https://openusd.org/release/spec_usdz.html).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace obscura::test {

using PackageEntries = std::vector<std::pair<std::string, std::string>>;  // name, contents

// `entries` as a package at `archive` (its folder made), in this order: the first layer is the
// package's root layer. "" when written, else why not.
std::string writePackage(const std::filesystem::path& archive, const PackageEntries& entries);

}  // namespace obscura::test
