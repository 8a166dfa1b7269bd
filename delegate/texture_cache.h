// The delegate's material textures: each distinct (file, sourceColorSpace, role) is read (from a
// file, or from a USDZ package in memory: assets/asset_reader.h) and uploaded once, with its full
// mip chain, and shared by every material naming it for as long as one holds it. With compression
// on, where the device samples the format, 8-bit normal maps are BC5-compressed (bc5_encoder.h) and
// 8-bit colour BC1 or BC3 (colour_block_compression.h), their blocks kept in a TextureDiskCache. A
// UDIM set (udim_tiles.h) is one atlas texture of its tiles, stored as any other. Also the
// samplers of the UsdUVTexture wrap modes and the white texture that fills the descriptor elements
// no material uses.
#pragma once

#include "assets/asset_reader.h"
#include "delegate/texture_disk_cache.h"
#include "delegate/texture_image.h"
#include "gpu/device.h"
#include "gpu/log.h"

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

namespace obscura::delegate {

// UsdUVTexture inputs:wrapS / wrapT (UsdPreviewSurface spec). useMetadata reads as repeat, the
// spec's choice when the file says nothing; file metadata is not consulted.
enum class WrapMode { Repeat, Clamp, Mirror, Black };
WrapMode parseWrapMode(const std::string& token);

struct Texture {
    gpu::ImagePtr image;
    std::array<float, 4> average{};  // TextureImage::average
    std::array<float, 4> renormScale{1.0f, 1.0f, 1.0f, 1.0f};  // TextureImage::renormScale
    std::array<float, 4> renormBias{};                          // TextureImage::renormBias
    bool twoChannelNormal = false;  // x and y of a normal map; the shader reconstructs z
    bool srgbEncoded = false;       // sampled as its sRGB-encoded values; the shader decodes after filtering
    std::array<float, 4> udimGrid{};       // UdimAtlas::grid; zero columns when not a UDIM set
    std::vector<std::string> leftOutTiles;  // UdimAtlas::leftOut
};
using TexturePtr = std::shared_ptr<const Texture>;

class TextureCache {
public:
    TextureCache(gpu::Device& device, LogSink log, TextureDiskCache diskCache);
    ~TextureCache();
    TextureCache(const TextureCache&) = delete;
    TextureCache& operator=(const TextureCache&) = delete;

    // The texture of an absolute file path or package path ("/dir/a.usdz[tex/b.png]", read from the
    // archive in memory; assets/asset_reader.h), or of a UDIM pattern (its tiles' atlas), read on
    // first use (logged at info level as "loaded texture <file> (size format, mips, device
    // memory)"), else the reason it cannot be read. Failures are not remembered: the next sync of
    // a material tries again.
    std::variant<TexturePtr, std::string> get(const std::string& file, SourceColorSpace colorSpace, TextureRole role);
    // Trilinear, anisotropic where the device allows and `anisotropic` asks; black is a transparent
    // black border.
    VkSampler sampler(WrapMode s, WrapMode t, bool anisotropic = true);
    const gpu::ImagePtr& white() const { return white_; }
    // The textures:compression render setting: textures loaded from now on.
    void setCompression(bool on) { compression_ = on; }

private:
    struct Made {
        gpu::ImageDesc desc;
        std::vector<gpu::MipLevel> levels;  // the levels not given are blitted
        std::string how;                    // for the log: how the levels were made
    };
    std::variant<TexturePtr, std::string> make(const std::string& file, SourceColorSpace colorSpace, TextureRole role);
    std::variant<TexturePtr, std::string> makeUdim(assets::AssetReader& assets, const std::string& pattern,
                                                   SourceColorSpace colorSpace, TextureRole role);
    // A decoded image with its mips, block-compressed where it may be. `sourceHashes` are the
    // TextureDiskCache::contentHash of the files its texels come from and `sourceEncoding` how they
    // were combined, for the disk cache's key. A compressed texture of one file stores under
    // `summaryKey` (unless empty) what cachedColourTexture needs to make it again undecoded.
    TexturePtr makeFromImage(const std::string& file, const std::vector<std::string>& sourceHashes,
                             const std::string& sourceEncoding, TextureImage image, TextureRole role, Texture texture,
                             const std::string& summaryKey);
    // A single file's block-compressed material texture made from the disk cache alone, its summary
    // under `summaryKey` and its blocks (the file's header not even read); null where the cache
    // lacks either or the device cannot sample the blocks' format.
    TexturePtr cachedColourTexture(const std::string& file, const std::vector<std::string>& sourceHashes,
                                   const std::string& summaryKey);
    // `bytes` (of `file`) as a two-channel normal map; nullopt: stored as the texture it is instead.
    std::optional<std::variant<TexturePtr, std::string>> makeNormalMap(const std::string& file, std::string_view bytes);
    TexturePtr upload(const std::string& file, Made made, Texture texture);
    bool canSampleCompressed(VkFormat format) const;
    // Block-compressed levels of the extents' sizes, `encode(i)` making level i, read from the disk
    // cache under (source contents, encoding) when it holds them (`cached`), else encoded and stored.
    std::vector<gpu::MipLevel> blockLevels(const std::vector<std::string>& sourceHashes, const std::string& encoding,
                                           const std::vector<gpu::MipLevel>& extents, VkFormat format,
                                           const std::function<gpu::MipLevel(size_t)>& encode, bool& cached) const;
    // The block-compressed levels of the extents' sizes the disk cache holds under `key`, followed
    // by `summary.size()` bytes it reads into `summary` (what the texture keeps of its texels beside
    // them); nullopt where it holds no entry of that size.
    std::optional<std::vector<gpu::MipLevel>> cachedBlockLevels(const std::string& key,
                                                                const std::vector<gpu::MipLevel>& extents,
                                                                VkFormat format, std::vector<std::byte>& summary) const;
    // `levels`, then `summary`, stored under `key`.
    void storeBlockLevels(const std::string& key, const std::vector<gpu::MipLevel>& levels,
                          const std::vector<std::byte>& summary) const;

    gpu::Device& device_;
    LogSink log_;
    TextureDiskCache diskCache_;
    bool compression_ = true;
    std::map<std::tuple<std::string, SourceColorSpace, TextureRole, bool>, std::weak_ptr<const Texture>> textures_;
    std::map<std::tuple<WrapMode, WrapMode, bool>, VkSampler> samplers_;
    gpu::ImagePtr white_;
};

}  // namespace obscura::delegate
