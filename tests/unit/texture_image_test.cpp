// The CPU mip filters: for formats the GPU cannot blit, a 2x2 box, in linear space for sRGB; for
// sRGB textures filtered in their encoded values, area means of that reconstruction.
#include "delegate/texture_image.h"

#include <Imath/half.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace obscura::delegate {
namespace {

gpu::MipLevel rgba8(uint32_t width, uint32_t height, const std::vector<uint8_t>& bytes) {
    gpu::MipLevel level{width, height, {}};
    for (uint8_t b : bytes) level.bytes.push_back(std::byte{b});
    return level;
}

int byteAt(const gpu::MipLevel& level, size_t i) { return std::to_integer<int>(level.bytes.at(i)); }

TEST(TextureMips, UnormAveragesTheStoredValues) {
    auto next = downsample(rgba8(2, 2, {0, 10, 255, 255, 100, 10, 255, 255, 0, 10, 0, 255, 100, 30, 0, 255}),
                           VK_FORMAT_R8G8B8A8_UNORM);
    ASSERT_EQ(next.width, 1u);
    ASSERT_EQ(next.height, 1u);
    EXPECT_EQ(byteAt(next, 0), 50);
    EXPECT_EQ(byteAt(next, 1), 15);
    EXPECT_EQ(byteAt(next, 2), 128);  // 127.5 rounds up
    EXPECT_EQ(byteAt(next, 3), 255);
}

TEST(TextureMips, SrgbAveragesInLinearSpace) {
    // Black and white average to linear 0.5, sRGB code 188 (not 128, the mean of the codes);
    // alpha is linear in sRGB formats.
    auto next = downsample(rgba8(2, 2, {0, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 0, 255, 255, 255, 255}),
                           VK_FORMAT_R8G8B8A8_SRGB);
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(byteAt(next, c), 188) << "channel " << c;
    EXPECT_EQ(byteAt(next, 3), 128);
}

TEST(TextureMips, HalfFloatsKeepTheirRange) {
    gpu::MipLevel level{2, 1, std::vector<std::byte>(2 * 8)};
    const Imath::half values[8] = {Imath::half(1000.0f), Imath::half(0.5f),  Imath::half(0.0f), Imath::half(1.0f),
                                   Imath::half(3000.0f), Imath::half(0.25f), Imath::half(2.0f), Imath::half(1.0f)};
    std::memcpy(level.bytes.data(), values, sizeof(values));
    auto next = downsample(level, VK_FORMAT_R16G16B16A16_SFLOAT);
    ASSERT_EQ(next.width, 1u);
    ASSERT_EQ(next.height, 1u);
    Imath::half out[4];
    std::memcpy(out, next.bytes.data(), sizeof(out));
    EXPECT_FLOAT_EQ(float(out[0]), 2000.0f);
    EXPECT_FLOAT_EQ(float(out[1]), 0.375f);
    EXPECT_FLOAT_EQ(float(out[2]), 1.0f);
    EXPECT_FLOAT_EQ(float(out[3]), 1.0f);
}

TEST(TextureMips, OddSizesHalveDownAndOneStaysOne) {
    auto next = downsample(rgba8(3, 1, std::vector<uint8_t>(12, 60)), VK_FORMAT_R8G8B8A8_UNORM);
    EXPECT_EQ(next.width, 1u);
    EXPECT_EQ(next.height, 1u);
    EXPECT_EQ(byteAt(next, 0), 60);
}

float srgbDecode(int code) {
    const double c = code / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

// A 16x16 one-texel black and white checker: below level 0 each texel is the mean of
// decode(bilinear of the bytes) over its footprint. Over a period that integrates to 0.2462
// (TextureTest.MinifiedTextureIntegratesItsReconstruction integrates it); the chain's 4 x 4 points
// a texel give 0.2424, within an 8-bit step. The mean of the decoded texels would be 0.5 (code 188).
TEST(TextureMips, EncodedReconstructionIntegratesTheDecodedBilinear) {
    std::vector<uint8_t> bytes;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 4; ++c) bytes.push_back((x + y) % 2 ? 255 : 0);
    auto chain = encodedReconstructionMips(rgba8(16, 16, bytes), 5);
    ASSERT_EQ(chain.size(), 5u);
    EXPECT_EQ(byteAt(chain[0], 4), 255);  // level 0 as it was
    // Level 1's texel (3, 3) covers texels 6 and 7 along each axis, away from the clamped border.
    const gpu::MipLevel& level1 = chain[1];
    ASSERT_EQ(level1.width, 8u);
    for (size_t c = 0; c < 3; ++c) {
        const int code = byteAt(level1, (3 * 8 + 3) * 4 + c);
        EXPECT_NEAR(srgbDecode(code), 0.2462f, 0.006f) << "channel " << c << " code " << code;
    }
    EXPECT_NEAR(byteAt(level1, (3 * 8 + 3) * 4 + 3), 128, 1);  // alpha: a box of 0 and 255
    EXPECT_EQ(chain[4].width, 1u);
}

// A texture of one colour keeps it at every level (the table's decode and the level's encode
// round-trip each code).
TEST(TextureMips, EncodedReconstructionKeepsAFlatColour) {
    for (int code : {0, 1, 30, 128, 200, 255}) {
        auto chain = encodedReconstructionMips(rgba8(4, 2, std::vector<uint8_t>(32, uint8_t(code))), 3);
        ASSERT_EQ(chain.size(), 3u);
        EXPECT_EQ(chain[2].width, 1u);
        EXPECT_EQ(chain[2].height, 1u);
        for (size_t c = 0; c < 4; ++c) EXPECT_EQ(byteAt(chain[2], c), code) << "code " << code << " channel " << c;
    }
}

}  // namespace
}  // namespace obscura::delegate
