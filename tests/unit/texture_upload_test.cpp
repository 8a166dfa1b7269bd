// Mip chains of gpu/texture_upload on the device: levels made by blits and levels given by the
// CPU (the fallback for formats that cannot be blitted) are read back level by level, with the
// validation layer on and no error allowed.
#include "gpu/texture_upload.h"

#include "tests/unit/validated_device_test.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <vector>

namespace obscura::gpu {
namespace {

class TextureUpload : public ValidatedDeviceTest {
protected:

    // The bytes of one level of a texture createMipmappedTexture left SHADER_READ_ONLY_OPTIMAL.
    std::vector<uint8_t> readLevel(const Image& image, uint32_t level, size_t texelBytes) {
        uint32_t width = std::max(image.desc.width >> level, 1u), height = std::max(image.desc.height >> level, 1u);
        VkDeviceSize size = VkDeviceSize(width) * height * texelBytes;
        auto buffer = device_->createBuffer(size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "readback");
        device_->context().submitAndWait([&](VkCommandBuffer cmd) {
            auto barrier = [&](VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 src,
                               VkPipelineStageFlags2 dst, VkAccessFlags2 srcAccess, VkAccessFlags2 dstAccess) {
                VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
                b.srcStageMask = src;
                b.dstStageMask = dst;
                b.srcAccessMask = srcAccess;
                b.dstAccessMask = dstAccess;
                b.oldLayout = from;
                b.newLayout = to;
                b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
                b.image = image.image;
                b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1};
                VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
                dep.imageMemoryBarrierCount = 1;
                dep.pImageMemoryBarriers = &b;
                vkCmdPipelineBarrier2(cmd, &dep);
            };
            barrier(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                    VK_ACCESS_2_TRANSFER_READ_BIT);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
            region.imageExtent = {width, height, 1};
            vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer->buffer, 1, &region);
            barrier(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE,
                    VK_ACCESS_2_SHADER_READ_BIT);
        });
        std::vector<uint8_t> out(size);
        std::memcpy(out.data(), buffer->mapped(), size);
        return out;
    }

    static MipLevel rgba8(uint32_t width, uint32_t height, const std::vector<uint8_t>& reds) {
        MipLevel level{width, height, {}};
        for (uint8_t r : reds)
            level.bytes.insert(level.bytes.end(), {std::byte{r}, std::byte{0}, std::byte{0}, std::byte{255}});
        return level;
    }

};

TEST(MipLevelCount, ReachesOneTexel) {
    EXPECT_EQ(mipLevelCount(1, 1), 1u);
    EXPECT_EQ(mipLevelCount(2, 1), 2u);
    EXPECT_EQ(mipLevelCount(5, 3), 3u);  // 5x3, 2x1, 1x1
    EXPECT_EQ(mipLevelCount(256, 64), 9u);
}

// Red channels of a 4x4 level: columns 0 and 1 hold 0, columns 2 and 3 hold 200.
std::vector<uint8_t> halves() {
    std::vector<uint8_t> reds;
    for (int y = 0; y < 4; ++y) reds.insert(reds.end(), {0, 0, 200, 200});
    return reds;
}

std::vector<int> redsOf(const std::vector<uint8_t>& rgba) {
    std::vector<int> reds;
    for (size_t i = 0; i < rgba.size(); i += 4) reds.push_back(rgba[i]);
    return reds;
}

ImageDesc rgba8Desc(uint32_t size) {
    ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = desc.height = size;
    desc.mipLevels = mipLevelCount(size, size);
    desc.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // for readLevel
    return desc;
}

TEST_F(TextureUpload, BlitsAverageEachLevelFromTheOneAbove) {
    ASSERT_TRUE(canBlitMips(*device_, VK_FORMAT_R8G8B8A8_UNORM));
    auto image = createMipmappedTexture(*device_, rgba8Desc(4), {rgba8(4, 4, halves())}, "blitted");
    const std::vector<uint8_t> level0 = halves();
    EXPECT_EQ(redsOf(readLevel(*image, 0, 4)), std::vector<int>(level0.begin(), level0.end()));
    auto level1 = redsOf(readLevel(*image, 1, 4));
    ASSERT_EQ(level1.size(), 4u);
    for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(level1[i], i % 2 ? 200 : 0, 1) << "texel " << i;
    auto level2 = redsOf(readLevel(*image, 2, 4));
    ASSERT_EQ(level2.size(), 1u);
    EXPECT_NEAR(level2[0], 100, 1);
}

TEST_F(TextureUpload, GivenLevelsAreKeptAndTheRestBlittedFromTheLast) {
    // Level 1 is deliberately not the average of level 0: level 2 must come from level 1.
    auto image =
        createMipmappedTexture(*device_, rgba8Desc(4), {rgba8(4, 4, halves()), rgba8(2, 2, {80, 80, 80, 80})}, "given");
    EXPECT_EQ(redsOf(readLevel(*image, 1, 4)), (std::vector<int>{80, 80, 80, 80}));
    EXPECT_NEAR(redsOf(readLevel(*image, 2, 4)).at(0), 80, 1);
}

TEST_F(TextureUpload, EveryLevelGivenIsUploadedAsIs) {
    auto image = createMipmappedTexture(*device_, rgba8Desc(4),
                                        {rgba8(4, 4, halves()), rgba8(2, 2, {1, 2, 3, 4}), rgba8(1, 1, {7})}, "cpu");
    EXPECT_EQ(redsOf(readLevel(*image, 1, 4)), (std::vector<int>{1, 2, 3, 4}));
    EXPECT_EQ(redsOf(readLevel(*image, 2, 4)), std::vector<int>{7});
}

}  // namespace
}  // namespace obscura::gpu
