#include "assets/asset_reader.h"

#include "assets/package_path.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace obscura::assets {
namespace {

std::optional<std::string> readFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

}  // namespace

std::optional<std::string> AssetReader::read(const std::string& path, std::string* error) {
    if (const auto packaged = splitPackagePath(path)) {
        const UsdzPackage* archive = package(packaged->package, error);
        return archive ? archive->read(packaged->entry, error) : std::nullopt;
    }
    auto bytes = readFile(path);
    if (!bytes) *error = "cannot read the file";
    return bytes;
}

const UsdzPackage* AssetReader::package(const std::string& path, std::string* error) {
    if (const auto it = packages_.find(path); it != packages_.end()) return it->second.get();
    std::unique_ptr<UsdzPackage> opened;
    if (splitPackagePath(path)) {
        // A package inside another is read whole from it; a package on disk is read as asked.
        auto bytes = read(path, error);
        if (bytes) opened = UsdzPackage::open(std::move(*bytes), error);
    } else {
        opened = UsdzPackage::openFile(path, error);
    }
    if (!opened) return nullptr;
    return (packages_[path] = std::move(opened)).get();
}

}  // namespace obscura::assets
