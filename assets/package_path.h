// USD's package-relative asset paths: "dir/a.usdz[tex/b.png]" names the file tex/b.png inside the
// package dir/a.usdz, and a package inside a package nests, "a.usdz[b.usdz[c.png]]" (OpenUSD's
// ArJoinPackageRelativePath and ArSplitPackageRelativePathInner). The one owner of that syntax
// for the harness, which resolves layers and texture paths, and the plugin, which reads textures.
// XXX: brackets inside a name are not escaped (Ar writes them as \[ and \]).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace obscura::assets {

struct PackagePath {
    std::string package;  // a file, or itself a package path: "a.usdz[b.usdz]"
    std::string entry;    // a file's name inside it: "c.png"
};

// "a.usdz[b.usdz[c.png]]" -> {"a.usdz[b.usdz]", "c.png"}: the innermost package and the file in
// it; nullopt for a path that names no file in a package.
std::optional<PackagePath> splitPackagePath(std::string_view path);
// The inverse: `entry` inside `package` ("a.usdz[b.usdz]", "c.png" -> "a.usdz[b.usdz[c.png]]").
std::string joinPackagePath(std::string_view package, std::string_view entry);

// Where `asset`, written in the layer `layer` (a file path or a package path), points, as USD's
// default resolver anchors it: a relative path to the layer's folder, inside a package to the
// layer's folder in the package, and a package path's package like any asset while the part
// inside stays as written. Normalised lexically (no file is looked at); a relative layer gives a
// relative result.
std::string anchorAssetPath(std::string_view asset, std::string_view layer);

// `path` with its file (a package path's outermost package) made absolute against the working
// folder and normalised lexically; the part inside a package is kept as it is. As written when
// the working folder cannot be found.
std::string absoluteAssetPath(std::string_view path);

}  // namespace obscura::assets
