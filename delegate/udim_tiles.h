// UDIM texture sets (schemas/udim_pattern.h: a <UDIM> file path names tiles 1001 + u + 10 v, each
// covering the st square [u, u + 1) x [v, v + 1)). Pure CPU code: finding a set's tiles, as files
// or in a USDZ package, and assembling them into one atlas texture, laid out like the squares they
// cover, that the shaders sample (shaders/common/material_inputs.glsl, sampleUdim).
#pragma once

#include "assets/asset_reader.h"
#include "delegate/texture_image.h"
#include "schemas/udim_pattern.h"

#include <array>
#include <string>
#include <variant>
#include <vector>

namespace obscura::delegate {

using schema::isUdimPattern;

struct UdimTile {
    int number = 0;  // 1001 + u + 10 v
    std::string file;  // a file path, or a package path
};

// The tiles of the set that exist, in tile order: 1001 to 1999 (u 0..9, v 0..99), the numbers the
// convention has. A pattern in a package ("a.usdz[tex/b.<UDIM>.png]") finds the package's files
// it names; the reason when the package cannot be opened.
std::variant<std::vector<UdimTile>, std::string> findUdimTiles(assets::AssetReader& assets,
                                                               const std::string& pattern);

struct UdimAtlas {
    TextureImage image;  // its average is the mean over the tiles that exist
    // st of the atlas's lower-left square (first u, first v) and the grid's columns and rows: the
    // atlas's texel (x, y) lies in the square (first u + x / cell width, first v + rows - 1 -
    // y / cell height). MaterialTexture::udimGrid.
    std::array<float, 4> grid{};
    std::vector<std::string> tileHashes;  // the placed tiles' TextureDiskCache::contentHash, for its key
    std::vector<std::string> leftOut;     // "<file>: <reason>" for each tile that could not be placed
};

// The atlas of `tiles`, read through `assets`: each grid cell holds its tile resampled to the
// cell's size (the largest tile's width and height rounded up to powers of two, at least 4 texels
// so that block compression's 4x4 blocks and the mips down to that size stay inside a cell), halved
// until the atlas fits `maxDimension`; squares with no tile are transparent black. Tiles are
// decoded as TextureRole::Plain: a 16-bit file is read as 8 bits (one renormalisation could not
// serve tiles of different ranges). A tile that cannot be read, or whose format differs from the
// first tile's (sRGB against linear, 8-bit against float), is left out. The reason when none is
// placed.
std::variant<UdimAtlas, std::string> assembleUdimAtlas(const std::vector<UdimTile>& tiles,
                                                       assets::AssetReader& assets, SourceColorSpace colorSpace,
                                                       uint32_t maxDimension);

}  // namespace obscura::delegate
