// USDZ packages: uncompressed zip archives whose first .usd, .usda or .usdc file is the root
// layer (https://openusd.org/release/spec_usdz.html). Files inside are named by package paths,
// "dir/scene.usdz[textures/a.png]", and read from the archive in memory, never unpacked.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

struct zip;  // libzip's archive handle

namespace obscura::usda {

// "a.usdz[b/c.usda]" -> {"a.usdz", "b/c.usda"} (the last bracketed part); nullopt otherwise.
std::optional<std::pair<std::string, std::string>> splitPackagePath(std::string_view path);
std::string joinPackagePath(const std::string& archive, const std::string& entry);

// A file inside a package ("a.usdz[tex/b.png]") as a path that readers of plain files (the
// delegate's texture loader) can open: extracted once per process into a temporary folder that
// is removed at exit. A UDIM set ("a.usdz[tex/b.<UDIM>.png]", schemas/udim_pattern.h) becomes a
// pattern they can expand: the tiles the package holds, and nothing else, extracted into one
// folder under their names, and the pattern's path in it (a token in a folder's name finds no
// tile). "" (and `error` set) when it cannot be read or the package holds no tile of the set.
std::string extractPackagedFile(const std::string& packagePath, std::string* error);

class UsdzPackage {
public:
    // The archive from its bytes; on failure returns nullptr and sets `error`.
    static std::unique_ptr<UsdzPackage> open(std::string bytes, std::string* error);
    // The archive in the file at `path`.
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
    std::string bytes_;
    ::zip* archive_ = nullptr;
    std::string rootLayer_;
};

}  // namespace obscura::usda
