// String helpers for USD scene paths ("/World/Mesh", "/World/Mesh.points", "/Asset{lod=hi}/Geom").
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace obscura::usda::sdfpath {

// A valid prim, property-namespace or variant name component: [A-Za-z_][A-Za-z0-9_]*, UTF-8 allowed
// (well-formed sequences only).
bool isIdentifier(std::string_view name);
// The offset of the first byte that is not part of well-formed UTF-8 (RFC 3629: no overlong
// forms, no surrogates, nothing above U+10FFFF), or npos.
size_t invalidUtf8At(std::string_view text);

std::string appendChild(std::string_view parent, std::string_view name);
// "/A/B" -> "/A", "/A" -> "/". Variant selections stay with their prim: "/A{v=x}/B" -> "/A{v=x}".
std::string parentOf(std::string_view path);
std::string nameOf(std::string_view path);
// Prim components below the root: "/" -> 0, "/A/B" -> 2.
int depthOf(std::string_view path);
// "/A{v=x}/B{w=y}" -> "/A/B".
std::string stripVariants(std::string_view path);

// Whether `prefix` is `path` or one of its ancestors (prim or property), component-wise.
bool hasPrefix(std::string_view path, std::string_view prefix);
// `path` with the ancestor `from` replaced by `to`; unchanged when `from` is not an ancestor.
std::string replacePrefix(std::string_view path, std::string_view from, std::string_view to);

// Resolves a path as written in a layer: absolute paths as they are, relative ones ("Child",
// "../Sibling.prop", ".prop") against the prim that authors them. nullopt when it climbs above "/".
std::optional<std::string> makeAbsolute(std::string_view path, std::string_view anchorPrim);

}  // namespace obscura::usda::sdfpath
