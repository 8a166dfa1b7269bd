// Buffers shared with another VkDevice (or a GL context) on the same GPU, for the ABI's display
// interop: device-local buffers in dedicated, exportable memory handed out as opaque file
// descriptors (VK_KHR_external_memory_fd), and the timeline semaphore the frames that write them
// signal (VK_KHR_external_semaphore_fd) after releasing them to VK_QUEUE_FAMILY_EXTERNAL.
#pragma once

#include "gpu/device.h"

#include <vector>

namespace obscura::gpu {

// How the importer allocates the memory behind a descriptor: for opaque fds the size and type
// must be those of the export (VkImportMemoryFdInfoKHR).
struct ExportedMemory {
    int fd = -1;  // owned by the caller
    VkDeviceSize allocationSize = 0;
    uint32_t memoryTypeIndex = 0;
    bool dedicated = true;
};

// A device-local buffer alone in an allocation that can be exported as an opaque fd. Destroyed at
// the end of the frame that last used it, like every buffer. Throws DeviceError when the device
// cannot export memory.
BufferPtr createExportableBuffer(Device& device, VkDeviceSize size, VkBufferUsageFlags usage);
// A new descriptor of the memory of a buffer made by createExportableBuffer.
ExportedMemory exportMemory(Device& device, const Buffer& buffer);

// The timeline semaphore of exported buffers and the release that ends each frame writing them.
class ExportTimeline {
public:
    explicit ExportTimeline(Device& device);
    ~ExportTimeline();
    ExportTimeline(const ExportTimeline&) = delete;
    ExportTimeline& operator=(const ExportTimeline&) = delete;

    // A new descriptor of the semaphore (the caller owns it), or -1 where the device cannot
    // export timeline semaphores.
    int exportSemaphore();
    // After the frame that wrote `buffers` (submitted on the device's queue): release them to
    // VK_QUEUE_FAMILY_EXTERNAL and signal the next value, in one submission after the frame's.
    // Returns the value, which the semaphore reaches when that submission is done.
    uint64_t release(const std::vector<BufferPtr>& buffers);
    uint64_t value() const { return value_; }

private:
    Device& device_;
    VkSemaphore semaphore_ = VK_NULL_HANDLE;  // null where semaphores cannot be exported
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    uint64_t value_ = 0;
};

}  // namespace obscura::gpu
