#include "delegate/texture_cache.h"

#include "gpu/texture_upload.h"
#include "gpu/vk_check.h"

#include <algorithm>

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
        default: return "RGBA16F";
    }
}

}  // namespace

WrapMode parseWrapMode(const std::string& token) {
    if (token == "clamp") return WrapMode::Clamp;
    if (token == "mirror") return WrapMode::Mirror;
    if (token == "black") return WrapMode::Black;
    return WrapMode::Repeat;
}

TextureCache::TextureCache(gpu::Device& device, LogSink log) : device_(device), log_(std::move(log)) {
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = desc.height = 1;
    const uint8_t white[4] = {255, 255, 255, 255};
    white_ = device_.createTextureWithData(desc, white, sizeof(white), "white texture");
}

TextureCache::~TextureCache() {
    for (const auto& [modes, sampler] : samplers_) vkDestroySampler(device_.vk(), sampler, nullptr);
}

std::variant<TexturePtr, std::string> TextureCache::get(const std::string& file, SourceColorSpace colorSpace) {
    auto key = std::make_pair(file, colorSpace);
    if (auto it = textures_.find(key); it != textures_.end())
        if (TexturePtr shared = it->second.lock()) return shared;

    auto decoded = decodeTextureFile(file, colorSpace);
    if (auto* problem = std::get_if<std::string>(&decoded)) return *problem;
    TextureImage& image = std::get<TextureImage>(decoded);
    gpu::ImageDesc desc;
    desc.format = image.format;
    desc.width = image.level0.width;
    desc.height = image.level0.height;
    desc.mipLevels = gpu::mipLevelCount(desc.width, desc.height);
    // Blits filter sRGB formats in linear space, as the CPU fallback does.
    const bool blit = gpu::canBlitMips(device_, desc.format);
    std::vector<gpu::MipLevel> levels;
    levels.push_back(std::move(image.level0));
    while (!blit && levels.size() < desc.mipLevels) levels.push_back(downsample(levels.back(), desc.format));

    auto texture = std::make_shared<Texture>();
    texture->image = gpu::createMipmappedTexture(device_, desc, levels, file.c_str());
    texture->average = image.average;
    textures_[key] = texture;
    log_(LogLevel::Info, "loaded texture " + file + " (" + std::to_string(desc.width) + "x" +
                             std::to_string(desc.height) + " " + formatName(desc.format) + ", " +
                             std::to_string(desc.mipLevels) + " mip levels " +
                             (blit ? "blitted" : "filtered on the CPU") + ")");
    return texture;
}

VkSampler TextureCache::sampler(WrapMode s, WrapMode t) {
    VkSampler& sampler = samplers_[{s, t}];
    if (sampler) return sampler;
    const gpu::Context& context = device_.context();
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = addressMode(s);
    si.addressModeV = addressMode(t);
    si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    si.anisotropyEnable = context.enabledFeatures().samplerAnisotropy;
    si.maxAnisotropy = std::min(16.0f, context.properties().limits.maxSamplerAnisotropy);
    si.maxLod = VK_LOD_CLAMP_NONE;
    gpu::vkCheck(vkCreateSampler(device_.vk(), &si, nullptr, &sampler), "vkCreateSampler");
    return sampler;
}

}  // namespace obscura::delegate
