#include "delegate/texture_image.h"

#include "delegate/texture_renormalization.h"

#include <Imath/half.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfVersion.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <thread>

namespace obscura::delegate {
namespace {

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

// IEC 61966-2-1 transfer functions.
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float linearToSrgb(float l) { return l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f; }

const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (size_t i = 0; i < t.size(); ++i) t[i] = srgbToLinear(float(i) / 255.0f);
        return t;
    }();
    return table;
}

// Texel channel as a sampler returns it (alpha is linear in sRGB formats).
float readChannel(const std::byte* texel, VkFormat format, size_t channel) {
    if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        Imath::half h;
        std::memcpy(&h, texel + 2 * channel, sizeof(h));
        return float(h);
    }
    auto code = static_cast<uint8_t>(texel[channel]);
    return format == VK_FORMAT_R8G8B8A8_SRGB && channel < 3 ? srgbTable()[code] : float(code) / 255.0f;
}

void writeChannel(std::byte* texel, VkFormat format, size_t channel, float value) {
    if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        Imath::half h(value);
        std::memcpy(texel + 2 * channel, &h, sizeof(h));
        return;
    }
    float encoded = format == VK_FORMAT_R8G8B8A8_SRGB && channel < 3 ? linearToSrgb(value) : value;
    texel[channel] = std::byte(static_cast<uint8_t>(std::lround(std::clamp(encoded, 0.0f, 1.0f) * 255.0f)));
}

std::array<float, 4> averageOf(const gpu::MipLevel& level, VkFormat format) {
    std::array<double, 4> sum{};
    const size_t stride = bytesPerTexel(format);
    for (size_t offset = 0; offset < level.bytes.size(); offset += stride)
        for (size_t c = 0; c < 4; ++c) sum[c] += readChannel(&level.bytes[offset], format, c);
    const double count = double(level.bytes.size() / stride);
    return {float(sum[0] / count), float(sum[1] / count), float(sum[2] / count), float(sum[3] / count)};
}

// Half floats hold up to 65504; larger radiance saturates there instead of becoming infinite
// (which filtering would spread), and NaN becomes 0.
Imath::half toHalf(float v) {
    constexpr float kMaxHalf = 65504.0f;
    return Imath::half(std::isnan(v) ? 0.0f : std::clamp(v, -kMaxHalf, kMaxHalf));
}

gpu::MipLevel halfLevel(uint32_t width, uint32_t height, const Imath::half* rgba) {
    gpu::MipLevel level{width, height, std::vector<std::byte>(size_t(width) * height * 8)};
    std::memcpy(level.bytes.data(), rgba, level.bytes.size());
    return level;
}

std::variant<TextureImage, std::string> decodeExr(std::string_view bytes) {
    try {
        Imf::StdISStream stream;
        stream.str(std::string(bytes));
        // RgbaInputFile fills channels the file lacks (alpha 1, luminance-only files as grey).
        Imf::RgbaInputFile file(stream);
        const Imath::Box2i window = file.dataWindow();
        const auto width = static_cast<uint32_t>(window.max.x - window.min.x + 1);
        const auto height = static_cast<uint32_t>(window.max.y - window.min.y + 1);
        Imf::Array2D<Imf::Rgba> pixels(height, width);
        file.setFrameBuffer(&pixels[0][0] - ptrdiff_t(window.min.x) - ptrdiff_t(window.min.y) * ptrdiff_t(width), 1,
                            width);
        file.readPixels(window.min.y, window.max.y);
        std::vector<Imath::half> rgba;
        rgba.reserve(size_t(width) * height * 4);
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x) {
                const Imf::Rgba& p = pixels[y][x];
                for (Imath::half c : {p.r, p.g, p.b, p.a}) rgba.push_back(toHalf(float(c)));
            }
        TextureImage image{VK_FORMAT_R16G16B16A16_SFLOAT, halfLevel(width, height, rgba.data()), {}};
        image.average = averageOf(image.level0, image.format);
        return image;
    } catch (const std::exception& e) {
        return std::string("cannot read OpenEXR file: ") + e.what();
    }
}

std::variant<TextureImage, std::string> decodeHdr(StbBytes bytes) {
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, StbFree> data(stbi_loadf_from_memory(bytes.data, bytes.size, &width, &height, &channels, 4));
    if (!data) return "cannot read image: " + stbFailureReason();
    std::vector<Imath::half> rgba(size_t(width) * size_t(height) * 4);
    std::transform(data.get(), data.get() + rgba.size(), rgba.begin(), toHalf);
    TextureImage image{VK_FORMAT_R16G16B16A16_SFLOAT, halfLevel(uint32_t(width), uint32_t(height), rgba.data()), {}};
    image.average = averageOf(image.level0, image.format);
    return image;
}

bool decodesSrgb(SourceColorSpace colorSpace, int fileChannels) {
    return colorSpace == SourceColorSpace::Srgb ||
           (colorSpace == SourceColorSpace::Auto && (fileChannels == 3 || fileChannels == 4));
}

std::variant<TextureImage, std::string> decode8Bit(StbBytes bytes, SourceColorSpace colorSpace) {
    int width = 0, height = 0, fileChannels = 0;
    std::unique_ptr<stbi_uc, StbFree> data(
        stbi_load_from_memory(bytes.data, bytes.size, &width, &height, &fileChannels, 4));
    if (!data) return "cannot read image: " + stbFailureReason();
    const bool srgb = decodesSrgb(colorSpace, fileChannels);
    TextureImage image;
    image.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    image.level0 = {uint32_t(width), uint32_t(height), std::vector<std::byte>(size_t(width) * size_t(height) * 4)};
    std::memcpy(image.level0.bytes.data(), data.get(), image.level0.bytes.size());
    image.average = averageOf(image.level0, image.format);
    return image;
}

// A 16-bit PNG: decoded to linear values at full precision and renormalised, or (when that would
// be coarser than 8-bit sRGB somewhere) read again as 8 bits.
std::variant<TextureImage, std::string> decode16Bit(StbBytes bytes, SourceColorSpace colorSpace) {
    int width = 0, height = 0, fileChannels = 0;
    std::unique_ptr<stbi_us, StbFree> data(
        stbi_load_16_from_memory(bytes.data, bytes.size, &width, &height, &fileChannels, 4));
    if (!data) return "cannot read image: " + stbFailureReason();
    const bool srgb = decodesSrgb(colorSpace, fileChannels);
    std::vector<float> linear(size_t(width) * size_t(height) * 4);
    for (size_t i = 0; i < linear.size(); ++i) {
        const float v = float(data.get()[i]) / 65535.0f;
        linear[i] = srgb && i % 4 < 3 ? srgbToLinear(v) : v;
    }
    auto stretched = renormalize(uint32_t(width), uint32_t(height), linear, srgb);
    if (!stretched) return decode8Bit(bytes, colorSpace);
    TextureImage image;
    image.format = VK_FORMAT_R8G8B8A8_UNORM;
    image.level0 = std::move(stretched->level);
    image.average = averageOf(image.level0, image.format);
    image.renormScale = stretched->scale;
    image.renormBias = stretched->bias;
    return image;
}

}  // namespace

std::string stbFailureReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown error";
}

size_t bytesPerTexel(VkFormat format) { return format == VK_FORMAT_R16G16B16A16_SFLOAT ? 8 : 4; }

SourceColorSpace parseSourceColorSpace(const std::string& token) {
    if (token == "sRGB") return SourceColorSpace::Srgb;
    if (token == "raw") return SourceColorSpace::Raw;
    return SourceColorSpace::Auto;
}

std::optional<StbBytes> StbBytes::of(std::string_view bytes) {
    if (bytes.size() > size_t(std::numeric_limits<int>::max())) return std::nullopt;
    return StbBytes{reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size())};
}

bool isOpenExr(std::string_view bytes) { return bytes.size() >= 4 && Imf::isImfMagic(bytes.data()); }

std::variant<TextureImage, std::string> decodeTextureImage(std::string_view bytes, SourceColorSpace colorSpace,
                                                           TextureRole role) {
    if (isOpenExr(bytes)) return decodeExr(bytes);
    const auto stb = StbBytes::of(bytes);
    if (!stb) return std::string(StbBytes::kTooLarge);
    if (stbi_is_hdr_from_memory(stb->data, stb->size)) return decodeHdr(*stb);
    if (role == TextureRole::Material && stbi_is_16_bit_from_memory(stb->data, stb->size))
        return decode16Bit(*stb, colorSpace);
    return decode8Bit(*stb, colorSpace);
}

gpu::MipLevel downsample(const gpu::MipLevel& level, VkFormat format) {
    const size_t stride = bytesPerTexel(format);
    gpu::MipLevel out{std::max(level.width / 2, 1u), std::max(level.height / 2, 1u), {}};
    out.bytes.resize(size_t(out.width) * out.height * stride);
    auto texel = [&](uint32_t x, uint32_t y) {
        return &level.bytes[(size_t(std::min(y, level.height - 1)) * level.width + std::min(x, level.width - 1)) *
                            stride];
    };
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x)
            for (size_t c = 0; c < 4; ++c) {
                float sum = readChannel(texel(2 * x, 2 * y), format, c) +
                            readChannel(texel(2 * x + 1, 2 * y), format, c) +
                            readChannel(texel(2 * x, 2 * y + 1), format, c) +
                            readChannel(texel(2 * x + 1, 2 * y + 1), format, c);
                writeChannel(&out.bytes[(size_t(y) * out.width + x) * stride], format, c, 0.25f * sum);
            }
    return out;
}

std::vector<gpu::MipLevel> encodedReconstructionMips(gpu::MipLevel level0, uint32_t levels, uint32_t cellWidth,
                                                     uint32_t cellHeight) {
    // decode(k / (64 * 255)): a point of the bilinear reconstruction at eighths between texel
    // centres is an integer combination of bytes in 64ths, so the table decodes it exactly.
    static const std::vector<float> decodeTable = [] {
        std::vector<float> t(64 * 255 + 1);
        for (size_t k = 0; k < t.size(); ++k) t[k] = srgbToLinear(float(double(k) / (64.0 * 255.0)));
        return t;
    }();
    const uint32_t w = level0.width, h = level0.height;
    const int64_t cw = cellWidth ? cellWidth : w, ch = cellHeight ? cellHeight : h;
    // Texel (x, y) of the cell that holds (cx, cy), clamped at the cell's border.
    auto texel = [&](int64_t cx, int64_t cy, int64_t x, int64_t y) {
        x = std::clamp<int64_t>(x, cx / cw * cw, std::min<int64_t>(cx / cw * cw + cw, w) - 1);
        y = std::clamp<int64_t>(y, cy / ch * ch, std::min<int64_t>(cy / ch * ch + ch, h) - 1);
        return reinterpret_cast<const uint8_t*>(&level0.bytes[(size_t(y) * w + size_t(x)) * 4]);
    };
    // Each texel's square in four quadrants, each between the texel, its neighbours along x and y
    // towards it and the diagonal one; 2 x 2 points a quadrant, 1/8 and 3/8 from the centre.
    auto texelMean = [&](uint32_t x, uint32_t y) {
        const uint8_t* centre = texel(x, y, x, y);
        std::array<float, 4> sum{0.0f, 0.0f, 0.0f, 16.0f * float(centre[3]) / 255.0f};
        for (int sy : {-1, 1})
            for (int sx : {-1, 1}) {
                const uint8_t* across = texel(x, y, int64_t(x) + sx, y);
                const uint8_t* along = texel(x, y, x, int64_t(y) + sy);
                const uint8_t* diagonal = texel(x, y, int64_t(x) + sx, int64_t(y) + sy);
                for (int ky : {1, 3})
                    for (int kx : {1, 3}) {
                        const int wc = (8 - kx) * (8 - ky), wx = kx * (8 - ky);
                        const int wy = (8 - kx) * ky, wd = kx * ky;
                        for (size_t c = 0; c < 3; ++c)
                            sum[c] += decodeTable[size_t(wc * centre[c] + wx * across[c] + wy * along[c] +
                                                         wd * diagonal[c])];
                    }
            }
        return sum;  // 16 times the mean
    };
    if (levels < 2) return {std::move(level0)};
    // Level 1 straight from the texels' means (a 2x2 box, an odd last row or column dropped), in
    // bands of rows across the machine's cores: 16 decodes a channel and texel (about 0.5 s for a
    // 2048² texture on one core), where the box of decoded texels took 4.
    uint32_t mw = std::max(w / 2, 1u), mh = std::max(h / 2, 1u);
    std::vector<std::array<float, 4>> means(size_t(mw) * mh);
    auto integrateRows = [&](uint32_t firstRow, uint32_t endRow) {
        for (uint32_t y = firstRow; y < endRow; ++y)
            for (uint32_t x = 0; x < mw; ++x) {
                std::array<float, 4> box{};
                for (uint32_t dy : {0u, 1u})
                    for (uint32_t dx : {0u, 1u}) {
                        const std::array<float, 4> m =
                            texelMean(std::min(2 * x + dx, w - 1), std::min(2 * y + dy, h - 1));
                        for (size_t c = 0; c < 4; ++c) box[c] += m[c] / 64.0f;
                    }
                means[size_t(y) * mw + x] = box;
            }
    };
    const uint32_t bands = std::clamp(std::thread::hardware_concurrency(), 1u, std::max(mh / 32, 1u));
    std::vector<std::thread> workers;
    for (uint32_t b = 1; b < bands; ++b) workers.emplace_back(integrateRows, mh * b / bands, mh * (b + 1) / bands);
    integrateRows(0, mh / bands);
    for (std::thread& worker : workers) worker.join();
    auto encoded = [](uint32_t width, uint32_t height, const std::vector<std::array<float, 4>>& level) {
        gpu::MipLevel out{width, height, std::vector<std::byte>(size_t(width) * height * 4)};
        for (size_t i = 0; i < level.size(); ++i)
            for (size_t c = 0; c < 4; ++c) writeChannel(&out.bytes[i * 4], VK_FORMAT_R8G8B8A8_SRGB, c, level[i][c]);
        return out;
    };
    std::vector<gpu::MipLevel> chain;
    chain.push_back(std::move(level0));
    chain.push_back(encoded(mw, mh, means));
    while (chain.size() < levels) {
        const uint32_t nw = std::max(mw / 2, 1u), nh = std::max(mh / 2, 1u);
        std::vector<std::array<float, 4>> next(size_t(nw) * nh);
        auto mean = [&](uint32_t px, uint32_t py) -> const std::array<float, 4>& {
            return means[size_t(std::min(py, mh - 1)) * mw + std::min(px, mw - 1)];
        };
        for (uint32_t y = 0; y < nh; ++y)
            for (uint32_t x = 0; x < nw; ++x)
                for (size_t c = 0; c < 4; ++c)
                    next[size_t(y) * nw + x][c] = 0.25f * (mean(2 * x, 2 * y)[c] + mean(2 * x + 1, 2 * y)[c] +
                                                           mean(2 * x, 2 * y + 1)[c] + mean(2 * x + 1, 2 * y + 1)[c]);
        means = std::move(next);
        mw = nw, mh = nh;
        chain.push_back(encoded(mw, mh, means));
    }
    return chain;
}

gpu::MipLevel resample(const gpu::MipLevel& level, VkFormat format, uint32_t width, uint32_t height) {
    if (level.width == width && level.height == height) return level;
    if (level.width >= 2 * width && level.height >= 2 * height)
        return resample(downsample(level, format), format, width, height);
    const size_t stride = bytesPerTexel(format);
    gpu::MipLevel out{width, height, std::vector<std::byte>(size_t(width) * height * stride)};
    auto read = [&](int64_t x, int64_t y, size_t c) {
        x = std::clamp<int64_t>(x, 0, level.width - 1);
        y = std::clamp<int64_t>(y, 0, level.height - 1);
        return readChannel(&level.bytes[(size_t(y) * level.width + size_t(x)) * stride], format, c);
    };
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const float sx = (float(x) + 0.5f) * float(level.width) / float(width) - 0.5f;
            const float sy = (float(y) + 0.5f) * float(level.height) / float(height) - 0.5f;
            const auto x0 = int64_t(std::floor(sx)), y0 = int64_t(std::floor(sy));
            const float fx = sx - float(x0), fy = sy - float(y0);
            for (size_t c = 0; c < 4; ++c) {
                const float top = read(x0, y0, c) * (1 - fx) + read(x0 + 1, y0, c) * fx;
                const float bottom = read(x0, y0 + 1, c) * (1 - fx) + read(x0 + 1, y0 + 1, c) * fx;
                writeChannel(&out.bytes[(size_t(y) * width + x) * stride], format, c, top * (1 - fy) + bottom * fy);
            }
        }
    return out;
}

}  // namespace obscura::delegate
