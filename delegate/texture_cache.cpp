#include "delegate/texture_cache.h"

#include "delegate/colour_block_compression.h"
#include "delegate/normal_map_image.h"
#include "delegate/udim_tiles.h"
#include "gpu/texture_upload.h"
#include "gpu/vk_check.h"

#include <algorithm>
#include <cstring>

namespace obscura::delegate {
namespace {

VkSamplerAddressMode addressMode(WrapMode mode) {
    switch (mode) {
        case WrapMode::Clamp: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case WrapMode::Mirror: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        case WrapMode::Black: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
        default: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    }
}

const char* formatName(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_SRGB: return "RGBA8 sRGB";
        case VK_FORMAT_R8G8B8A8_UNORM: return "RGBA8";
        case VK_FORMAT_R16G16_UNORM: return "RG16";
        case VK_FORMAT_BC5_UNORM_BLOCK: return "BC5";
        case VK_FORMAT_BC1_RGB_SRGB_BLOCK: return "BC1 sRGB";
        case VK_FORMAT_BC1_RGB_UNORM_BLOCK: return "BC1";
        case VK_FORMAT_BC3_SRGB_BLOCK: return "BC3 sRGB";
        case VK_FORMAT_BC3_UNORM_BLOCK: return "BC3";
        default: return "RGBA16F";
    }
}

// The UNORM twin an sRGB format is sampled through (ImageDesc::sampledAs); VK_FORMAT_UNDEFINED
// for the others.
VkFormat encodedTwin(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_SRGB: return VK_FORMAT_R8G8B8A8_UNORM;
        case VK_FORMAT_BC1_RGB_SRGB_BLOCK: return VK_FORMAT_BC1_RGB_UNORM_BLOCK;
        case VK_FORMAT_BC3_SRGB_BLOCK: return VK_FORMAT_BC3_UNORM_BLOCK;
        default: return VK_FORMAT_UNDEFINED;
    }
}

// Whether a texture of `role` decoded to `format` is filtered in its encoded values and decoded
// in the shader (TextureCache::makeFromImage): a material's sRGB texels.
bool decodedInShader(TextureRole role, VkFormat format) {
    return role != TextureRole::Plain && encodedTwin(format) != VK_FORMAT_UNDEFINED;
}

// The encoding a block-compressed colour chain is stored under in the disk cache.
std::string colourBlockEncoding(const std::string& sourceEncoding, VkFormat blockFormat, VkFormat sourceFormat) {
    return sourceEncoding + "squish-2-" + std::to_string(blockFormat) + "-from-" + std::to_string(sourceFormat);
}

// What a single file's block-compressed material texture keeps in the disk cache beside its
// blocks, so that a later load makes it from the cache without decoding the file: the formats that
// name the blocks' entry, the size, the texels' mean (Texture::average).
struct ColourSummary {
    uint32_t blockFormat = 0, sourceFormat = 0, width = 0, height = 0;
    std::array<float, 4> average{};
    // What makeFromImage writes; a damaged cache file reads as a miss, and no unknown format
    // reaches the device.
    bool plausible() const {
        const auto block = VkFormat(blockFormat), source = VkFormat(sourceFormat);
        const bool knownBlock = block == VK_FORMAT_BC1_RGB_SRGB_BLOCK || block == VK_FORMAT_BC1_RGB_UNORM_BLOCK ||
                                block == VK_FORMAT_BC3_SRGB_BLOCK || block == VK_FORMAT_BC3_UNORM_BLOCK;
        const bool knownSource = source == VK_FORMAT_R8G8B8A8_SRGB || source == VK_FORMAT_R8G8B8A8_UNORM;
        return knownBlock && knownSource && width > 0 && height > 0;
    }
};

// The sizes of a full mip chain of `desc` (each level half the last, down to one texel).
std::vector<gpu::MipLevel> mipExtents(const gpu::ImageDesc& desc) {
    std::vector<gpu::MipLevel> extents;
    for (uint32_t i = 0; i < desc.mipLevels; ++i)
        extents.push_back({std::max(desc.width >> i, 1u), std::max(desc.height >> i, 1u), {}});
    return extents;
}

size_t blockBytes(VkFormat format) {
    return format == VK_FORMAT_BC1_RGB_SRGB_BLOCK || format == VK_FORMAT_BC1_RGB_UNORM_BLOCK ? 8 : 16;
}

size_t blockLevelBytes(const gpu::MipLevel& level, VkFormat format) {
    return size_t((level.width + 3) / 4) * ((level.height + 3) / 4) * blockBytes(format);
}

}  // namespace

WrapMode parseWrapMode(const std::string& token) {
    if (token == "clamp") return WrapMode::Clamp;
    if (token == "mirror") return WrapMode::Mirror;
    if (token == "black") return WrapMode::Black;
    return WrapMode::Repeat;
}

TextureCache::TextureCache(gpu::Device& device, LogSink log, TextureDiskCache diskCache)
    : device_(device), log_(std::move(log)), diskCache_(std::move(diskCache)) {
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = desc.height = 1;
    const uint8_t white[4] = {255, 255, 255, 255};
    white_ = device_.createTextureWithData(desc, white, sizeof(white), "white texture");
}

TextureCache::~TextureCache() {
    for (const auto& [modes, sampler] : samplers_) vkDestroySampler(device_.vk(), sampler, nullptr);
}

std::variant<TexturePtr, std::string> TextureCache::get(const std::string& file, SourceColorSpace colorSpace,
                                                        TextureRole role) {
    auto key = std::make_tuple(file, colorSpace, role, compression_);
    if (auto it = textures_.find(key); it != textures_.end())
        if (TexturePtr shared = it->second.lock()) return shared;
    auto made = make(file, colorSpace, role);
    if (auto* texture = std::get_if<TexturePtr>(&made)) textures_[key] = *texture;
    return made;
}

std::variant<TexturePtr, std::string> TextureCache::make(const std::string& file, SourceColorSpace colorSpace,
                                                         TextureRole role) {
    // A reader of this load's own: a UDIM set's tiles in one package share one opening of it,
    // and a package changed on disk is read anew by the next load.
    assets::AssetReader assets;
    if (isUdimPattern(file)) return makeUdim(assets, file, colorSpace, role);
    std::string problem;
    const std::optional<std::string> bytes = assets.read(file, &problem);
    if (!bytes) return problem;
    if (role == TextureRole::Normal)
        if (auto normalMap = makeNormalMap(file, *bytes)) return *normalMap;
    const std::string hash = TextureDiskCache::contentHash(*bytes);
    // Decoding a file of the texture's colour space gives the same texels each time.
    const std::string summaryKey = TextureDiskCache::key({hash}, "colour-summary-1-space-" + std::to_string(int(colorSpace)));
    if (role == TextureRole::Material && compression_)
        if (TexturePtr cached = cachedColourTexture(file, {hash}, summaryKey)) return cached;
    auto decoded = decodeTextureImage(*bytes, colorSpace, role);
    if (auto* undecodable = std::get_if<std::string>(&decoded)) return *undecodable;
    return makeFromImage(file, {hash}, "", std::move(std::get<TextureImage>(decoded)), role, Texture{}, summaryKey);
}

TexturePtr TextureCache::cachedColourTexture(const std::string& file, const std::vector<std::string>& sourceHashes,
                                             const std::string& summaryKey) {
    const std::optional<std::vector<std::byte>> bytes = diskCache_.read(summaryKey);
    ColourSummary summary;
    if (!bytes || bytes->size() != sizeof(summary)) return nullptr;
    std::memcpy(&summary, bytes->data(), sizeof(summary));
    const uint32_t maxDimension = device_.context().properties().limits.maxImageDimension2D;
    if (!summary.plausible() || summary.width > maxDimension || summary.height > maxDimension) return nullptr;
    const auto blockFormat = VkFormat(summary.blockFormat), sourceFormat = VkFormat(summary.sourceFormat);
    if (!canSampleCompressed(blockFormat)) return nullptr;
    Made made;
    made.desc.format = blockFormat;
    made.desc.width = summary.width;
    made.desc.height = summary.height;
    made.desc.mipLevels = gpu::mipLevelCount(made.desc.width, made.desc.height);
    std::vector<std::byte> noSummary;
    auto levels = cachedBlockLevels(TextureDiskCache::key(sourceHashes, colourBlockEncoding("", blockFormat, sourceFormat)),
                                    mipExtents(made.desc), blockFormat, noSummary);
    if (!levels) return nullptr;
    made.levels = std::move(*levels);
    made.how = "filtered on the CPU, compressed (from the disk cache)";
    Texture texture;
    texture.srgbEncoded = decodedInShader(TextureRole::Material, sourceFormat);
    if (texture.srgbEncoded) made.desc.sampledAs = encodedTwin(blockFormat);
    texture.average = summary.average;
    return upload(file, std::move(made), std::move(texture));
}

std::variant<TexturePtr, std::string> TextureCache::makeUdim(assets::AssetReader& assets, const std::string& pattern,
                                                             SourceColorSpace colorSpace, TextureRole role) {
    auto found = findUdimTiles(assets, pattern);
    if (auto* problem = std::get_if<std::string>(&found)) return *problem;
    const std::vector<UdimTile>& tiles = std::get<std::vector<UdimTile>>(found);
    if (tiles.empty()) return std::string("no UDIM tile exists (1001 to 1999)");
    const uint32_t maxDimension = device_.context().properties().limits.maxImageDimension2D;
    auto assembled = assembleUdimAtlas(tiles, assets, colorSpace, maxDimension);
    if (auto* problem = std::get_if<std::string>(&assembled)) return *problem;
    UdimAtlas& atlas = std::get<UdimAtlas>(assembled);
    Texture texture;
    texture.udimGrid = atlas.grid;
    texture.leftOutTiles = std::move(atlas.leftOut);
    std::string layout = "udim-1";
    for (float g : atlas.grid) layout += "-" + std::to_string(int(g));
    layout += "-" + std::to_string(atlas.image.level0.width) + "x" + std::to_string(atlas.image.level0.height) + "-";
    // A normal map's set keeps its own z in RGBA (the two-channel route reads single files).
    return makeFromImage(pattern, atlas.tileHashes, layout, std::move(atlas.image),
                         role == TextureRole::Normal ? TextureRole::Plain : role, std::move(texture), "");
}

TexturePtr TextureCache::makeFromImage(const std::string& file, const std::vector<std::string>& sourceHashes,
                                       const std::string& sourceEncoding, TextureImage image, TextureRole role,
                                       Texture texture, const std::string& summaryKey) {
    Made made;
    made.desc.format = image.format;
    made.desc.width = image.level0.width;
    made.desc.height = image.level0.height;
    made.desc.mipLevels = gpu::mipLevelCount(made.desc.width, made.desc.height);
    // 8-bit colour is block-compressed where the device samples the format; renormalised
    // textures keep their 8 bits, whose precision was the point.
    const bool eightBit = image.format == VK_FORMAT_R8G8B8A8_SRGB || image.format == VK_FORMAT_R8G8B8A8_UNORM;
    const VkFormat blockFormat = role == TextureRole::Material && compression_ && eightBit && !image.renormalised()
                                     ? colourBlockFormat(image.level0, image.format)
                                     : VK_FORMAT_UNDEFINED;
    const bool compress = blockFormat != VK_FORMAT_UNDEFINED && canSampleCompressed(blockFormat);
    // A material's sRGB texture is filtered in its encoded values and decoded after (the shader's
    // MaterialTexture::encoding), as offline renderers filter 8-bit textures: Cycles interpolates
    // the bytes and converts to linear after, so a magnified texture's texels blend as in the
    // path-traced truth. Its mips are area means of that reconstruction in linear light, so that
    // a minified texture keeps the pixel's integral (encodedReconstructionMips); they are made on
    // the CPU (lavapipe blits a mutable-format image's sRGB levels in their encoded values).
    const bool inShader = decodedInShader(role, image.format);
    // Compressed formats cannot be blitted.
    const bool blit = !compress && !inShader && gpu::canBlitMips(device_, made.desc.format);
    const VkFormat sourceFormat = image.format;
    // A UDIM atlas's tiles are reconstructed apart (UdimAtlas::grid: columns, rows).
    const uint32_t cellWidth = texture.udimGrid[2] > 0.0f ? made.desc.width / uint32_t(texture.udimGrid[2]) : 0u;
    const uint32_t cellHeight = texture.udimGrid[3] > 0.0f ? made.desc.height / uint32_t(texture.udimGrid[3]) : 0u;
    auto cpuChain = [&] {
        if (inShader && sourceFormat == VK_FORMAT_R8G8B8A8_SRGB)
            return encodedReconstructionMips(std::move(image.level0), made.desc.mipLevels, cellWidth, cellHeight);
        std::vector<gpu::MipLevel> chain{std::move(image.level0)};
        while (chain.size() < made.desc.mipLevels) chain.push_back(downsample(chain.back(), sourceFormat));
        return chain;
    };
    made.how = std::string(blit ? "blitted" : "filtered on the CPU") + (image.renormalised() ? ", renormalised" : "");
    if (compress) {
        // The chain is made for the first level the disk cache lacks; a hit needs only the sizes.
        std::vector<gpu::MipLevel> chain;
        bool cached = false;
        made.levels = blockLevels(sourceHashes, colourBlockEncoding(sourceEncoding, blockFormat, sourceFormat),
                                  mipExtents(made.desc), blockFormat,
                                  [&](size_t i) {
                                      if (chain.empty()) chain = cpuChain();
                                      return compressColourLevel(chain[i], blockFormat);
                                  },
                                  cached);
        if (!summaryKey.empty()) {
            const ColourSummary summary{uint32_t(blockFormat), uint32_t(sourceFormat), made.desc.width,
                                        made.desc.height, image.average};
            std::vector<std::byte> bytes(sizeof(summary));
            std::memcpy(bytes.data(), &summary, sizeof(summary));
            diskCache_.write(summaryKey, bytes);
        }
        made.desc.format = blockFormat;
        made.how += cached ? ", compressed (from the disk cache)" : ", compressed on the CPU";
    } else if (blit) {
        made.levels.push_back(std::move(image.level0));
    } else {
        made.levels = cpuChain();
    }
    if (inShader) made.desc.sampledAs = encodedTwin(made.desc.format);
    texture.srgbEncoded = inShader;
    texture.average = image.average;
    texture.renormScale = image.renormScale;
    texture.renormBias = image.renormBias;
    return upload(file, std::move(made), std::move(texture));
}

std::optional<std::variant<TexturePtr, std::string>> TextureCache::makeNormalMap(const std::string& file,
                                                                                 std::string_view bytes) {
    // A float file keeps its values: it is stored as the texture it is.
    if (!isIntegerImage(bytes)) return std::nullopt;
    // 16-bit files keep their precision (the talk's "Normal maps precision"); 8-bit ones are
    // compressed, or left to the Material path as they always were when compression is off.
    const bool bc5 = !isSixteenBitImage(bytes);
    if (bc5 && !(compression_ && canSampleCompressed(VK_FORMAT_BC5_UNORM_BLOCK))) return std::nullopt;
    Made made;
    made.desc.format = bc5 ? VK_FORMAT_BC5_UNORM_BLOCK : VK_FORMAT_R16G16_UNORM;
    Texture texture;
    texture.twoChannelNormal = true;
    // x and y read back as 0.5 n + 0.5 of the normalised average, z 0 (two-channel formats). An
    // encoded map keeps the average's x and y after its blocks in the disk cache: a hit reads the
    // file's header alone, neither decoding its texels nor filtering its chain.
    auto setAverage = [&](float x, float y) { texture.average = {0.5f * x + 0.5f, 0.5f * y + 0.5f, 0.0f, 1.0f}; };
    std::vector<std::byte> average(2 * sizeof(float));
    const std::string key = TextureDiskCache::key({TextureDiskCache::contentHash(bytes)}, "bc5-normal-aware-2");
    if (auto extent = bc5 ? imageExtent(bytes) : std::nullopt) {
        made.desc.width = (*extent)[0];
        made.desc.height = (*extent)[1];
        made.desc.mipLevels = gpu::mipLevelCount(made.desc.width, made.desc.height);
        if (auto levels = cachedBlockLevels(key, mipExtents(made.desc), made.desc.format, average)) {
            made.levels = std::move(*levels);
            made.how = "filtered on the CPU, encoded (from the disk cache)";
            std::array<float, 2> xy{};
            std::memcpy(xy.data(), average.data(), average.size());
            setAverage(xy[0], xy[1]);
            return upload(file, std::move(made), std::move(texture));
        }
    }
    auto decoded = decodeNormalMap(bytes);
    if (auto* problem = std::get_if<std::string>(&decoded)) return *problem;
    NormalMapSource& source = std::get<NormalMapSource>(decoded);
    made.desc.width = source.normals.width;
    made.desc.height = source.normals.height;
    made.desc.mipLevels = gpu::mipLevelCount(made.desc.width, made.desc.height);
    // Mips of unit normals, normalised after averaging, on the CPU: BC5 cannot be blitted.
    std::vector<NormalImage> chain{std::move(source.normals)};
    while (chain.size() < made.desc.mipLevels) chain.push_back(downsampleNormals(chain.back()));
    const std::array<float, 3>& last = chain.back().normals[0];
    setAverage(last[0], last[1]);
    if (!bc5) {
        for (const NormalImage& level : chain) made.levels.push_back(packTwoChannels(level, made.desc.format));
        made.how = "filtered on the CPU";
    } else {
        for (const NormalImage& level : chain)
            made.levels.push_back({level.width, level.height, encodeBc5(level, Bc5Encoder::NormalAware)});
        std::memcpy(average.data(), last.data(), average.size());
        storeBlockLevels(key, made.levels, average);
        made.how = "filtered and encoded on the CPU";
    }
    return upload(file, std::move(made), std::move(texture));
}

bool TextureCache::canSampleCompressed(VkFormat format) const {
    if (!device_.context().enabledFeatures().textureCompressionBC) return false;
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(device_.context().physicalDevice(), format, &properties);
    const VkFormatFeatureFlags needed =
        VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    return (properties.optimalTilingFeatures & needed) == needed;
}

std::vector<gpu::MipLevel> TextureCache::blockLevels(const std::vector<std::string>& sourceHashes,
                                                     const std::string& encoding,
                                                     const std::vector<gpu::MipLevel>& extents, VkFormat format,
                                                     const std::function<gpu::MipLevel(size_t)>& encode,
                                                     bool& cached) const {
    const std::string key = TextureDiskCache::key(sourceHashes, encoding);
    std::vector<std::byte> noSummary;
    std::optional<std::vector<gpu::MipLevel>> levels = cachedBlockLevels(key, extents, format, noSummary);
    cached = levels.has_value();
    if (cached) return std::move(*levels);
    levels.emplace();
    for (size_t i = 0; i < extents.size(); ++i) levels->push_back(encode(i));
    storeBlockLevels(key, *levels, noSummary);
    return std::move(*levels);
}

std::optional<std::vector<gpu::MipLevel>> TextureCache::cachedBlockLevels(const std::string& key,
                                                                          const std::vector<gpu::MipLevel>& extents,
                                                                          VkFormat format,
                                                                          std::vector<std::byte>& summary) const {
    size_t total = summary.size();
    for (const gpu::MipLevel& level : extents) total += blockLevelBytes(level, format);
    std::optional<std::vector<std::byte>> blocks = diskCache_.read(key);
    if (!blocks || blocks->size() != total) return std::nullopt;
    std::vector<gpu::MipLevel> levels;
    auto at = blocks->begin();
    for (const gpu::MipLevel& level : extents) {
        const auto end = at + std::ptrdiff_t(blockLevelBytes(level, format));
        levels.push_back({level.width, level.height, std::vector<std::byte>(at, end)});
        at = end;
    }
    std::copy(at, blocks->end(), summary.begin());
    return levels;
}

void TextureCache::storeBlockLevels(const std::string& key, const std::vector<gpu::MipLevel>& levels,
                                    const std::vector<std::byte>& summary) const {
    std::vector<std::byte> bytes;
    for (const gpu::MipLevel& level : levels) bytes.insert(bytes.end(), level.bytes.begin(), level.bytes.end());
    bytes.insert(bytes.end(), summary.begin(), summary.end());
    diskCache_.write(key, bytes);
}

TexturePtr TextureCache::upload(const std::string& file, Made made, Texture texture) {
    texture.image = gpu::createMipmappedTexture(device_, made.desc, made.levels, file.c_str());
    log_(LogLevel::Info, "loaded texture " + file + " (" + std::to_string(made.desc.width) + "x" +
                             std::to_string(made.desc.height) + " " + formatName(made.desc.format) + ", " +
                             std::to_string(made.desc.mipLevels) + " mip levels " + made.how + ", " +
                             std::to_string(device_.imageMemoryRequirements(texture.image->desc).size / 1024) +
                             " KiB)");
    return std::make_shared<const Texture>(std::move(texture));
}

VkSampler TextureCache::sampler(WrapMode s, WrapMode t, bool anisotropic) {
    VkSampler& sampler = samplers_[{s, t, anisotropic}];
    if (sampler) return sampler;
    const gpu::Context& context = device_.context();
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = addressMode(s);
    si.addressModeV = addressMode(t);
    si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    si.anisotropyEnable = anisotropic && context.enabledFeatures().samplerAnisotropy;
    si.maxAnisotropy = std::min(16.0f, context.properties().limits.maxSamplerAnisotropy);
    si.maxLod = VK_LOD_CLAMP_NONE;
    gpu::vkCheck(vkCreateSampler(device_.vk(), &si, nullptr, &sampler), "vkCreateSampler");
    return sampler;
}

}  // namespace obscura::delegate
