#include "delegate/udim_tiles.h"

#include "assets/package_path.h"
#include "delegate/texture_disk_cache.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>

namespace obscura::delegate {
namespace {

constexpr uint32_t kMinCellSide = 4;  // a block-compression block

int tileU(int number) { return (number - schema::kFirstUdimTile) % 10; }
int tileV(int number) { return (number - schema::kFirstUdimTile) / 10; }

uint32_t cellSide(uint32_t largestTile) { return std::bit_ceil(std::max(largestTile, kMinCellSide)); }

}  // namespace

std::variant<std::vector<UdimTile>, std::string> findUdimTiles(assets::AssetReader& assets,
                                                               const std::string& pattern) {
    std::vector<UdimTile> tiles;
    if (const auto packaged = assets::splitPackagePath(pattern)) {
        std::string problem;
        const assets::UsdzPackage* package = assets.package(packaged->package, &problem);
        if (!package) return problem;
        for (const std::string& entry : package->entries())
            if (const auto number = schema::udimTileNumber(packaged->entry, entry))
                tiles.push_back({*number, assets::joinPackagePath(packaged->package, entry)});
        std::sort(tiles.begin(), tiles.end(),
                  [](const UdimTile& a, const UdimTile& b) { return a.number < b.number; });
        return tiles;
    }
    for (int number = schema::kFirstUdimTile; number <= schema::kLastUdimTile; ++number) {
        std::string file = schema::udimTilePath(pattern, number);
        std::error_code ec;
        if (std::filesystem::is_regular_file(file, ec)) tiles.push_back({number, std::move(file)});
    }
    return tiles;
}

std::variant<UdimAtlas, std::string> assembleUdimAtlas(const std::vector<UdimTile>& tiles,
                                                       assets::AssetReader& assets, SourceColorSpace colorSpace,
                                                       uint32_t maxDimension) {
    UdimAtlas atlas;
    struct Placed {
        int number;
        TextureImage image;
    };
    std::vector<Placed> placed;
    for (const UdimTile& tile : tiles) {
        std::string unreadable;
        const std::optional<std::string> bytes = assets.read(tile.file, &unreadable);
        if (!bytes) {
            atlas.leftOut.push_back(tile.file + ": " + unreadable);
            continue;
        }
        auto decoded = decodeTextureImage(*bytes, colorSpace, TextureRole::Plain);
        if (auto* problem = std::get_if<std::string>(&decoded)) {
            atlas.leftOut.push_back(tile.file + ": " + *problem);
            continue;
        }
        auto& image = std::get<TextureImage>(decoded);
        if (!placed.empty() && image.format != placed.front().image.format) {
            atlas.leftOut.push_back(tile.file + ": its texel format differs from the set's first tile's");
            continue;
        }
        placed.push_back({tile.number, std::move(image)});
        atlas.tileHashes.push_back(TextureDiskCache::contentHash(*bytes));
    }
    if (placed.empty()) return "no UDIM tile could be read";

    int firstU = 9, lastU = 0, firstV = 99, lastV = 0;
    uint32_t widest = 0, tallest = 0;
    for (const Placed& p : placed) {
        firstU = std::min(firstU, tileU(p.number));
        lastU = std::max(lastU, tileU(p.number));
        firstV = std::min(firstV, tileV(p.number));
        lastV = std::max(lastV, tileV(p.number));
        widest = std::max(widest, p.image.level0.width);
        tallest = std::max(tallest, p.image.level0.height);
    }
    const auto columns = uint32_t(lastU - firstU + 1), rows = uint32_t(lastV - firstV + 1);
    uint32_t cellWidth = cellSide(widest), cellHeight = cellSide(tallest);
    while (cellWidth > kMinCellSide && cellWidth * columns > maxDimension) cellWidth /= 2;
    while (cellHeight > kMinCellSide && cellHeight * rows > maxDimension) cellHeight /= 2;
    if (cellWidth * columns > maxDimension || cellHeight * rows > maxDimension)
        return "its " + std::to_string(columns) + "x" + std::to_string(rows) + " tiles exceed the device's " +
               std::to_string(maxDimension) + " texel texture size";

    TextureImage& out = atlas.image;
    out.format = placed.front().image.format;
    const size_t stride = bytesPerTexel(out.format);
    out.level0 = {cellWidth * columns, cellHeight * rows, {}};
    out.level0.bytes.resize(size_t(out.level0.width) * out.level0.height * stride);  // transparent black
    for (const Placed& p : placed) {
        const gpu::MipLevel cell = resample(p.image.level0, out.format, cellWidth, cellHeight);
        // Row 0 of an image is its top, t = 1 of its square: the highest v comes first.
        const size_t x0 = size_t(tileU(p.number) - firstU) * cellWidth;
        const size_t y0 = size_t(lastV - tileV(p.number)) * cellHeight;
        for (uint32_t y = 0; y < cellHeight; ++y)
            std::memcpy(&out.level0.bytes[((y0 + y) * out.level0.width + x0) * stride],
                        &cell.bytes[size_t(y) * cellWidth * stride], size_t(cellWidth) * stride);
        for (size_t c = 0; c < 4; ++c) out.average[c] += p.image.average[c] / float(placed.size());
    }
    atlas.grid = {float(firstU), float(firstV), float(columns), float(rows)};
    return atlas;
}

}  // namespace obscura::delegate
