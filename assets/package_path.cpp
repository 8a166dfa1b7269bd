#include "assets/package_path.h"

#include <filesystem>
#include <utility>

namespace obscura::assets {
namespace {

namespace fs = std::filesystem;

// "a.usdz[b.usdz[c.png]]" -> {"a.usdz", "b.usdz[c.png]"}: the outermost package and what is
// inside it, found by the bracket that matches the last one.
std::optional<std::pair<std::string_view, std::string_view>> splitOuter(std::string_view path) {
    if (!path.ends_with(']')) return std::nullopt;
    int depth = 0;
    for (size_t i = path.size(); i-- > 0;) {
        if (path[i] == ']') {
            ++depth;
        } else if (path[i] == '[' && --depth == 0) {
            if (i == 0 || i + 2 == path.size()) return std::nullopt;  // no package, or nothing inside
            return std::pair{path.substr(0, i), path.substr(i + 1, path.size() - i - 2)};
        }
    }
    return std::nullopt;
}

std::string normal(const fs::path& path) { return path.lexically_normal().string(); }

}  // namespace

std::optional<PackagePath> splitPackagePath(std::string_view path) {
    const auto outer = splitOuter(path);
    if (!outer) return std::nullopt;
    if (auto inner = splitPackagePath(outer->second))
        return PackagePath{joinPackagePath(outer->first, inner->package), std::move(inner->entry)};
    return PackagePath{std::string(outer->first), std::string(outer->second)};
}

std::string joinPackagePath(std::string_view package, std::string_view entry) {
    if (const auto outer = splitOuter(package))
        return std::string(outer->first) + "[" + joinPackagePath(outer->second, entry) + "]";
    return std::string(package) + "[" + std::string(entry) + "]";
}

std::string anchorAssetPath(std::string_view asset, std::string_view layer) {
    if (const auto packaged = splitPackagePath(asset))
        return joinPackagePath(anchorAssetPath(packaged->package, layer), normal(packaged->entry));
    const fs::path path(asset);
    if (path.is_absolute()) return normal(path);
    if (const auto inPackage = splitPackagePath(layer))
        return joinPackagePath(inPackage->package, normal(fs::path(inPackage->entry).parent_path() / path));
    return normal(fs::path(layer).parent_path() / path);
}

std::string absoluteAssetPath(std::string_view path) {
    if (const auto packaged = splitPackagePath(path))
        return joinPackagePath(absoluteAssetPath(packaged->package), packaged->entry);
    std::error_code ec;
    const fs::path absolute = fs::absolute(fs::path(path), ec);
    return normal(ec ? fs::path(path) : absolute);
}

}  // namespace obscura::assets
