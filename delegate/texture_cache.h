// The delegate's material textures: each distinct (file, sourceColorSpace) is read and uploaded
// once, with its full mip chain, and shared by every material naming it for as long as one holds
// it. Also the samplers of the UsdUVTexture wrap modes and the white texture that fills the
// descriptor elements no material uses.
#pragma once

#include "delegate/texture_image.h"
#include "gpu/device.h"
#include "gpu/log.h"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <variant>

namespace obscura::delegate {

// UsdUVTexture inputs:wrapS / wrapT (UsdPreviewSurface spec). useMetadata reads as repeat, the
// spec's choice when the file says nothing; file metadata is not consulted.
enum class WrapMode { Repeat, Clamp, Mirror, Black };
WrapMode parseWrapMode(const std::string& token);

struct Texture {
    gpu::ImagePtr image;
    std::array<float, 4> average{};  // TextureImage::average
};
using TexturePtr = std::shared_ptr<const Texture>;

class TextureCache {
public:
    TextureCache(gpu::Device& device, LogSink log);
    ~TextureCache();
    TextureCache(const TextureCache&) = delete;
    TextureCache& operator=(const TextureCache&) = delete;

    // The texture of an absolute file path, read on first use (logged at info level as
    // "loaded texture <file>"), else the reason it cannot be read. Failures are not remembered:
    // the next sync of a material tries again.
    std::variant<TexturePtr, std::string> get(const std::string& file, SourceColorSpace colorSpace);
    // Trilinear, anisotropic where the device allows; black is a transparent black border.
    VkSampler sampler(WrapMode s, WrapMode t);
    const gpu::ImagePtr& white() const { return white_; }

private:
    gpu::Device& device_;
    LogSink log_;
    std::map<std::pair<std::string, SourceColorSpace>, std::weak_ptr<const Texture>> textures_;
    std::map<std::pair<WrapMode, WrapMode>, VkSampler> samplers_;
    gpu::ImagePtr white_;
};

}  // namespace obscura::delegate
