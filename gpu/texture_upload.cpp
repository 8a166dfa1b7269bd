#include "gpu/texture_upload.h"

#include "gpu/vk_check.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace obscura::gpu {
namespace {

int32_t levelSize(uint32_t base, uint32_t level) { return static_cast<int32_t>(std::max(base >> level, 1u)); }

VkImageMemoryBarrier2 levelBarrier(VkImage image, uint32_t level, VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask =
        from == VK_IMAGE_LAYOUT_UNDEFINED ? VK_PIPELINE_STAGE_2_NONE : VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    b.srcAccessMask = from == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL ? VK_ACCESS_2_TRANSFER_WRITE_BIT : VK_ACCESS_2_NONE;
    b.dstStageMask = to == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL ? VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT
                                                                    : VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    b.dstAccessMask = to == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL ? VK_ACCESS_2_SHADER_READ_BIT
                      : to == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL   ? VK_ACCESS_2_TRANSFER_READ_BIT
                                                                     : VK_ACCESS_2_TRANSFER_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1};
    return b;
}

void barrier(VkCommandBuffer cmd, const std::vector<VkImageMemoryBarrier2>& barriers) {
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = static_cast<uint32_t>(barriers.size());
    dep.pImageMemoryBarriers = barriers.data();
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

uint32_t mipLevelCount(uint32_t width, uint32_t height) {
    return static_cast<uint32_t>(std::bit_width(std::max({width, height, 1u})));
}

bool canBlitMips(Device& device, VkFormat format) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(device.context().physicalDevice(), format, &properties);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    return (properties.optimalTilingFeatures & needed) == needed;
}

ImagePtr createMipmappedTexture(Device& device, const ImageDesc& descIn, const std::vector<MipLevel>& levels,
                                const char* debugName) {
    MemoryCategoryScope textures(MemoryCategory::Textures);
    ImageDesc desc = descIn;
    const auto given = static_cast<uint32_t>(std::min<size_t>(levels.size(), desc.mipLevels));
    desc.usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    if (given < desc.mipLevels) desc.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    auto image = device.createImage(desc, debugName);

    VkDeviceSize total = 0;
    for (uint32_t i = 0; i < given; ++i) total += levels[i].bytes.size();
    auto staging = device.createBuffer(total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
    std::vector<VkBufferImageCopy> copies;
    VkDeviceSize offset = 0;
    for (uint32_t i = 0; i < given; ++i) {
        std::memcpy(static_cast<std::byte*>(staging->mapped()) + offset, levels[i].bytes.data(),
                    levels[i].bytes.size());
        VkBufferImageCopy region{};
        region.bufferOffset = offset;
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, i, 0, 1};
        region.imageExtent = {levels[i].width, levels[i].height, 1};
        copies.push_back(region);
        offset += levels[i].bytes.size();
    }

    device.context().submitAndWait([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier2> toDst;
        for (uint32_t i = 0; i < desc.mipLevels; ++i)
            toDst.push_back(
                levelBarrier(image->image, i, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
        barrier(cmd, toDst);
        vkCmdCopyBufferToImage(cmd, staging->buffer, image->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               static_cast<uint32_t>(copies.size()), copies.data());
        // Each blitted level reads the one above it, which then stays a transfer source.
        std::vector<VkImageLayout> layouts(desc.mipLevels, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        for (uint32_t i = given; i < desc.mipLevels; ++i) {
            barrier(cmd, {levelBarrier(image->image, i - 1, layouts[i - 1], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)});
            layouts[i - 1] = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, i - 1, 0, 1};
            blit.srcOffsets[1] = {levelSize(desc.width, i - 1), levelSize(desc.height, i - 1), 1};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, i, 0, 1};
            blit.dstOffsets[1] = {levelSize(desc.width, i), levelSize(desc.height, i), 1};
            vkCmdBlitImage(cmd, image->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image->image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        }
        std::vector<VkImageMemoryBarrier2> toRead;
        for (uint32_t i = 0; i < desc.mipLevels; ++i)
            toRead.push_back(levelBarrier(image->image, i, layouts[i], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
        barrier(cmd, toRead);
    });
    image->layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    return image;
}

}  // namespace obscura::gpu
