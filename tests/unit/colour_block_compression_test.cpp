// BC1/BC3 compression of 8-bit colour textures (colour_block_compression.h).
#include "delegate/colour_block_compression.h"

#include <gtest/gtest.h>
#include <squish.h>

#include <cmath>

namespace obscura::delegate {
namespace {

gpu::MipLevel ramp(uint32_t width, uint32_t height, uint8_t alpha) {
    gpu::MipLevel level{width, height, {}};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const float t = float(x) / float(width - 1);
            for (float c : {20.0f + 210.0f * t, 60.0f + 120.0f * t, 200.0f - 160.0f * t})
                level.bytes.push_back(std::byte(uint8_t(std::lround(c))));
            level.bytes.push_back(std::byte{alpha});
        }
    return level;
}

TEST(ColourBlockCompression, OpaqueTexelsTakeBc1AndAlphaBc3) {
    EXPECT_EQ(colourBlockFormat(ramp(8, 8, 255), VK_FORMAT_R8G8B8A8_SRGB), VK_FORMAT_BC1_RGB_SRGB_BLOCK);
    EXPECT_EQ(colourBlockFormat(ramp(8, 8, 255), VK_FORMAT_R8G8B8A8_UNORM), VK_FORMAT_BC1_RGB_UNORM_BLOCK);
    EXPECT_EQ(colourBlockFormat(ramp(8, 8, 254), VK_FORMAT_R8G8B8A8_SRGB), VK_FORMAT_BC3_SRGB_BLOCK);
    EXPECT_EQ(compressColourLevel(ramp(6, 5, 255), VK_FORMAT_BC1_RGB_SRGB_BLOCK).bytes.size(), 2u * 2u * 8u);
    EXPECT_EQ(compressColourLevel(ramp(6, 5, 128), VK_FORMAT_BC3_SRGB_BLOCK).bytes.size(), 2u * 2u * 16u);
}

TEST(ColourBlockCompression, SmoothRampKeepsBc1sEndpointPrecision) {
    // A ramp's colours in a 4x4 block lie on a line, which BC1's palette (two endpoints and the
    // two colours a third of the way between) follows; what it cannot follow is the endpoints'
    // 5:6:5 precision: half a 5-bit step is 255 / 31 / 2 = 4.1 codes, so the error is at most
    // that and the PSNR at least 20 log10(255 / 4.1) = 35.9 dB.
    const gpu::MipLevel source = ramp(64, 64, 255);
    const gpu::MipLevel blocks = compressColourLevel(source, VK_FORMAT_BC1_RGB_SRGB_BLOCK);
    std::vector<squish::u8> decoded(source.bytes.size());
    squish::DecompressImage(decoded.data(), 64, 64, blocks.bytes.data(), squish::kDxt1);
    double squared = 0.0, worst = 0.0;
    for (size_t i = 0; i < decoded.size(); ++i) {
        if (i % 4 == 3) continue;
        const double d = double(decoded[i]) - double(std::to_integer<int>(source.bytes[i]));
        squared += d * d;
        worst = std::max(worst, std::abs(d));
    }
    const double psnr = 10.0 * std::log10(255.0 * 255.0 / (squared / double(decoded.size() / 4 * 3)));
    EXPECT_GE(psnr, 35.9) << "max error " << worst << " codes";
    EXPECT_LE(worst, 255.0 / 31.0 / 2.0 + 1.0);  // plus the palette's own rounding
}

}  // namespace
}  // namespace obscura::delegate
