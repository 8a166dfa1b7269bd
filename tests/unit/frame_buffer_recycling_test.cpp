// Device::createFrameBuffer on lavapipe: a frame that asks for the sizes of the last one gets the
// same buffers back and allocates nothing; buffers no frame asks for again are destroyed, so
// memory stays bounded while sizes change. Validation on, no error allowed.
#include "gpu/device.h"

#include "tests/unit/validated_device_test.h"

#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <vector>

namespace obscura::gpu {
namespace {

constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

class FrameBufferRecycling : public ValidatedDeviceTest {
protected:

    // One frame's records: buffers of the given sizes, released before the frame ends.
    std::set<VkBuffer> frame(const std::vector<VkDeviceSize>& sizes) {
        std::set<VkBuffer> handles;
        {
            std::vector<BufferPtr> buffers;
            for (VkDeviceSize size : sizes) {
                buffers.push_back(device_->createFrameBuffer(size, kUsage, "records"));
                EXPECT_EQ(buffers.back()->size, size);
                EXPECT_NE(buffers.back()->mapped(), nullptr);
                handles.insert(buffers.back()->buffer);
            }
        }
        device_->endFrame();
        return handles;
    }

};

TEST_F(FrameBufferRecycling, AnUnchangedFrameGetsTheSameBuffersAndAllocatesNothing) {
    const std::vector<VkDeviceSize> sizes = {256, 1024, 256, 4096};
    const std::set<VkBuffer> first = frame(sizes);
    const VkDeviceSize reserved = device_->memory().bytesReserved();
    const VkDeviceSize inUse = device_->memory().bytesInUse();
    for (int i = 0; i < 100; ++i) {
        EXPECT_EQ(frame(sizes), first) << "frame " << i;
        EXPECT_EQ(device_->memory().bytesInUse(), inUse);
        EXPECT_EQ(device_->memory().bytesReserved(), reserved);
    }
}

TEST_F(FrameBufferRecycling, ABufferStillHeldIsNotHandedOutTwice) {
    auto kept = device_->createFrameBuffer(512, kUsage, "kept");
    device_->endFrame();
    auto other = device_->createFrameBuffer(512, kUsage, "other");
    EXPECT_NE(kept->buffer, other->buffer);
}

TEST_F(FrameBufferRecycling, BuffersOfSizesNoLongerAskedForAreDestroyed) {
    frame({256});
    const VkDeviceSize baseline = device_->memory().bytesInUse();
    // A scene whose record counts change every frame: each frame asks for new sizes.
    for (VkDeviceSize size = 1 << 16; size < (1 << 16) + 64 * 256; size += 256) frame({size});
    // What is left is at most the last few frames' sizes, not one buffer per size ever used.
    EXPECT_LT(device_->memory().bytesInUse(), baseline + 8 * ((1 << 16) + 64 * 256));
    for (int i = 0; i < 8; ++i) frame({256});
    EXPECT_EQ(device_->memory().bytesInUse(), baseline);
}

}  // namespace
}  // namespace obscura::gpu
