// USDZ packages: uncompressed zip archives whose first .usd, .usda or .usdc file is the root
// layer (https://openusd.org/release/spec_usdz.html), read in memory through libzip, never
// unpacked. Files inside are named by package paths (package_path.h).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

struct zip;  // libzip's archive handle

namespace obscura::assets {

class UsdzPackage {
public:
    // The archive from its bytes; on failure returns nullptr and sets `error`.
    static std::unique_ptr<UsdzPackage> open(std::string bytes, std::string* error);
    // The archive in the file at `path`, whose files are read from it as they are asked for.
    static std::unique_ptr<UsdzPackage> openFile(const std::string& path, std::string* error);
    ~UsdzPackage();
    UsdzPackage(const UsdzPackage&) = delete;
    UsdzPackage& operator=(const UsdzPackage&) = delete;

    // The first layer file in the archive's order, or "" when it holds none.
    const std::string& rootLayer() const { return rootLayer_; }
    // A file's bytes; nullopt (and `error` set) when it is missing or unreadable.
    std::optional<std::string> read(const std::string& entry, std::string* error) const;
    // Every file's name, in the archive's order.
    std::vector<std::string> entries() const;

private:
    UsdzPackage() = default;
    void findRootLayer();
    std::string bytes_;  // the archive's bytes, when it was opened from them
    ::zip* archive_ = nullptr;
    std::string rootLayer_;
};

}  // namespace obscura::assets
