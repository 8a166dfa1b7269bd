// The CPU mip filter for formats the GPU cannot blit: a 2x2 box, in linear space for sRGB.
#include "delegate/texture_image.h"

#include <Imath/half.h>
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace obscura::delegate
