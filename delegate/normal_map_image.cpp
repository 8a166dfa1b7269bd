#include "delegate/normal_map_image.h"

#include "delegate/texture_image.h"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

namespace obscura::delegate {
namespace {

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

std::array<float, 3> normalised(float x, float y, float z) {
    const float length = std::sqrt(x * x + y * y + z * z);
    if (!(length > 0.0f)) return {0.0f, 0.0f, 1.0f};
    return {x / length, y / length, z / length};
}

template <typename T>
NormalImage toNormals(const T* rgb, int width, int height, float maxCode) {
    NormalImage image{uint32_t(width), uint32_t(height), {}};
    image.normals.reserve(size_t(width) * size_t(height));
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
        auto signedAt = [&](size_t c) { return 2.0f * float(rgb[i * 3 + c]) / maxCode - 1.0f; };
        image.normals.push_back(normalised(signedAt(0), signedAt(1), signedAt(2)));
    }
    return image;
}

}  // namespace

bool isIntegerImage(std::string_view bytes) {
    const auto stb = StbBytes::of(bytes);
    return stb && !isOpenExr(bytes) && !stbi_is_hdr_from_memory(stb->data, stb->size);
}

bool isSixteenBitImage(std::string_view bytes) {
    const auto stb = StbBytes::of(bytes);
    return stb && stbi_is_16_bit_from_memory(stb->data, stb->size);
}

std::optional<std::array<uint32_t, 2>> imageExtent(std::string_view bytes) {
    const auto stb = StbBytes::of(bytes);
    int width = 0, height = 0, channels = 0;
    if (!stb || !stbi_info_from_memory(stb->data, stb->size, &width, &height, &channels) || width <= 0 || height <= 0)
        return std::nullopt;
    return std::array<uint32_t, 2>{uint32_t(width), uint32_t(height)};
}

std::variant<NormalMapSource, std::string> decodeNormalMap(std::string_view bytes) {
    const auto stb = StbBytes::of(bytes);
    if (!stb) return std::string(StbBytes::kTooLarge);
    int width = 0, height = 0, channels = 0;
    NormalMapSource source;
    source.sixteenBit = isSixteenBitImage(bytes);
    if (source.sixteenBit) {
        std::unique_ptr<stbi_us, StbFree> data(
            stbi_load_16_from_memory(stb->data, stb->size, &width, &height, &channels, 3));
        if (!data) return "cannot read image: " + stbFailureReason();
        source.normals = toNormals(data.get(), width, height, 65535.0f);
    } else {
        std::unique_ptr<stbi_uc, StbFree> data(
            stbi_load_from_memory(stb->data, stb->size, &width, &height, &channels, 3));
        if (!data) return "cannot read image: " + stbFailureReason();
        source.normals = toNormals(data.get(), width, height, 255.0f);
    }
    return source;
}

NormalImage downsampleNormals(const NormalImage& level) {
    NormalImage out{std::max(level.width / 2, 1u), std::max(level.height / 2, 1u), {}};
    out.normals.reserve(size_t(out.width) * out.height);
    auto at = [&](uint32_t x, uint32_t y) {
        return level.normals[size_t(std::min(y, level.height - 1)) * level.width + std::min(x, level.width - 1)];
    };
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            std::array<float, 3> sum{};
            for (const auto& n : {at(2 * x, 2 * y), at(2 * x + 1, 2 * y), at(2 * x, 2 * y + 1), at(2 * x + 1, 2 * y + 1)})
                for (size_t c = 0; c < 3; ++c) sum[c] += n[c];
            out.normals.push_back(normalised(sum[0], sum[1], sum[2]));
        }
    return out;
}

gpu::MipLevel packTwoChannels(const NormalImage& level, VkFormat format) {
    const bool sixteen = format == VK_FORMAT_R16G16_UNORM;
    const float maxCode = sixteen ? 65535.0f : 255.0f;
    gpu::MipLevel out{level.width, level.height, std::vector<std::byte>(level.normals.size() * (sixteen ? 4 : 2))};
    for (size_t i = 0; i < level.normals.size(); ++i)
        for (size_t c = 0; c < 2; ++c) {
            const auto code = uint16_t(std::lround((0.5f * level.normals[i][c] + 0.5f) * maxCode));
            if (sixteen) std::memcpy(&out.bytes[i * 4 + c * 2], &code, sizeof(code));
            else out.bytes[i * 2 + c] = std::byte(uint8_t(code));
        }
    return out;
}

}  // namespace obscura::delegate
