#include "assets/asset_reader.h"

#include "assets/package_path.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace obscura::assets {
namespace {

std::optional<std::string> readFile(const std::string& path, std::string* error) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        *error = "no such file";
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in || std::filesystem::is_directory(path, ec)) {
        *error = "cannot be read";
        return std::nullopt;
    }
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
    return readFile(path, error);
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
