// The UDIM naming convention (Mari's, as OpenUSD's UsdUVTexture, Storm and MaterialX follow it): a
// file path holding <UDIM> names a set of tiles, the token standing for the tile number
// 1001 + u + 10 v of the st square [u, u + 1) x [v, v + 1). The delegate finds a set's tiles among
// files on disk by their paths, and among a USDZ package's files by their names.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace obscura::schema {

// The numbers the convention has: u 0..9, v 0..99.
constexpr int kFirstUdimTile = 1001, kLastUdimTile = 1999;

bool isUdimPattern(std::string_view path);
// `pattern` with its token replaced by `number`.
std::string udimTilePath(std::string_view pattern, int number);
// The tile number `path` names under `pattern`, nullopt when it names none (a number outside
// the convention's, or anything other than four digits where the token stands).
std::optional<int> udimTileNumber(std::string_view pattern, std::string_view path);

}  // namespace obscura::schema
