#include "gpu/external_memory.h"

#include "gpu/vk_check.h"

namespace obscura::gpu {
namespace {

uint32_t deviceLocalType(const VkPhysicalDeviceMemoryProperties& properties, uint32_t typeBits) {
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            return i;
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i)
        if (typeBits & (1u << i)) return i;
    throw DeviceError("no memory type for an exportable buffer");
}

}  // namespace

BufferPtr createExportableBuffer(Device& device, VkDeviceSize size, VkBufferUsageFlags usage) {
    Context& context = device.context();
    if (!context.externalHandles().memoryFd)
        throw DeviceError(context.summary().name + " cannot export memory (no VK_KHR_external_memory_fd)",
                          VK_ERROR_FEATURE_NOT_PRESENT);
    VkDevice vk = device.vk();
    auto* b = new Buffer();
    b->size = size;
    b->id = device.newResourceId();
    VkExternalMemoryBufferCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
    external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, &external};
    bi.size = size;
    bi.usage = usage;
    bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkResult r = vkCreateBuffer(vk, &bi, nullptr, &b->buffer);
    if (r != VK_SUCCESS) {
        delete b;
        vkCheck(r, "vkCreateBuffer (exportable)");
    }
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk, b->buffer, &req);
    // A dedicated allocation: the importer maps the whole of it to its own buffer.
    VkMemoryDedicatedAllocateInfo dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
    dedicated.buffer = b->buffer;
    VkExportMemoryAllocateInfo exportInfo{VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO, &dedicated};
    exportInfo.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &exportInfo};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = deviceLocalType(context.memoryProperties(), req.memoryTypeBits);
    r = context.faults().strikes(FaultInjection::Kind::OutOfMemory) ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                                                                     : vkAllocateMemory(vk, &ai, nullptr, &b->allocation.memory);
    if (r != VK_SUCCESS) {
        vkDestroyBuffer(vk, b->buffer, nullptr);
        delete b;
        vkCheck(r, "vkAllocateMemory (exportable)");
    }
    b->allocation.size = req.size;
    b->allocation.flags = context.memoryProperties().memoryTypes[ai.memoryTypeIndex].propertyFlags;
    vkCheck(vkBindBufferMemory(vk, b->buffer, b->allocation.memory, 0), "vkBindBufferMemory (exportable)");
    return BufferPtr(b, [&device](Buffer* p) {
        device.retire([&device, p] {
            vkDestroyBuffer(device.vk(), p->buffer, nullptr);
            vkFreeMemory(device.vk(), p->allocation.memory, nullptr);
            delete p;
        });
    });
}

ExportedMemory exportMemory(Device& device, const Buffer& buffer) {
    auto getFd = reinterpret_cast<PFN_vkGetMemoryFdKHR>(vkGetDeviceProcAddr(device.vk(), "vkGetMemoryFdKHR"));
    if (!getFd) throw DeviceError("vkGetMemoryFdKHR is not available", VK_ERROR_FEATURE_NOT_PRESENT);
    VkMemoryGetFdInfoKHR info{VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR};
    info.memory = buffer.allocation.memory;
    info.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    ExportedMemory out;
    vkCheck(getFd(device.vk(), &info, &out.fd), "vkGetMemoryFdKHR");
    out.allocationSize = buffer.allocation.size;
    // The type createExportableBuffer chose, chosen again from the same requirements.
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device.vk(), buffer.buffer, &req);
    out.memoryTypeIndex = deviceLocalType(device.context().memoryProperties(), req.memoryTypeBits);
    return out;
}

ExportTimeline::ExportTimeline(Device& device) : device_(device) {
    VkDevice vk = device.vk();
    if (device.context().externalHandles().semaphoreFd) {
        VkExportSemaphoreCreateInfo exportInfo{VK_STRUCTURE_TYPE_EXPORT_SEMAPHORE_CREATE_INFO};
        exportInfo.handleTypes = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
        VkSemaphoreTypeCreateInfo timeline{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO, &exportInfo};
        timeline.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &timeline};
        vkCheck(vkCreateSemaphore(vk, &si, nullptr, &semaphore_), "vkCreateSemaphore (exportable timeline)");
    }
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = device.context().commandPool();
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    vkCheck(vkAllocateCommandBuffers(vk, &ai, &commands_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vkCheck(vkCreateFence(vk, &fi, nullptr, &fence_), "vkCreateFence");
}

ExportTimeline::~ExportTimeline() {
    VkDevice vk = device_.vk();
    vkDeviceWaitIdle(vk);
    vkDestroyFence(vk, fence_, nullptr);
    vkFreeCommandBuffers(vk, device_.context().commandPool(), 1, &commands_);
    if (semaphore_) vkDestroySemaphore(vk, semaphore_, nullptr);
}

int ExportTimeline::exportSemaphore() {
    if (!semaphore_) return -1;
    auto getFd = reinterpret_cast<PFN_vkGetSemaphoreFdKHR>(vkGetDeviceProcAddr(device_.vk(), "vkGetSemaphoreFdKHR"));
    if (!getFd) return -1;
    VkSemaphoreGetFdInfoKHR info{VK_STRUCTURE_TYPE_SEMAPHORE_GET_FD_INFO_KHR};
    info.semaphore = semaphore_;
    info.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    int fd = -1;
    vkCheck(getFd(device_.vk(), &info, &fd), "vkGetSemaphoreFdKHR");
    return fd;
}

uint64_t ExportTimeline::release(const std::vector<BufferPtr>& buffers) {
    VkDevice vk = device_.vk();
    Context& context = device_.context();
    vkCheck(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(commands_, &bi), "vkBeginCommandBuffer");
    // The queue family ownership transfer external memory needs for another device to see the
    // frame's writes (Vulkan spec, "Queue Family Ownership Transfer", VK_QUEUE_FAMILY_EXTERNAL).
    // The next frame overwrites the buffer whole, so it takes it back without an acquire.
    std::vector<VkBufferMemoryBarrier2> releases;
    for (const BufferPtr& b : buffers) {
        VkBufferMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
        barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
        barrier.srcQueueFamilyIndex = context.queueFamily();
        barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_EXTERNAL;
        barrier.buffer = b->buffer;
        barrier.size = VK_WHOLE_SIZE;
        releases.push_back(barrier);
    }
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.bufferMemoryBarrierCount = static_cast<uint32_t>(releases.size());
    dependency.pBufferMemoryBarriers = releases.data();
    vkCmdPipelineBarrier2(commands_, &dependency);
    vkCheck(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");

    const uint64_t next = value_ + 1;
    VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    timeline.signalSemaphoreValueCount = 1;
    timeline.pSignalSemaphoreValues = &next;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO, semaphore_ ? &timeline : nullptr};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &commands_;
    si.signalSemaphoreCount = semaphore_ ? 1 : 0;
    si.pSignalSemaphores = &semaphore_;
    vkCheck(vkResetFences(vk, 1, &fence_), "vkResetFences");
    vkCheck(vkQueueSubmit(context.queue(), 1, &si, fence_), "vkQueueSubmit (interop release)");
    // render returns with its frame done on the device, exported buffers included (the ABI).
    vkCheck(vkWaitForFences(vk, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    value_ = next;
    return value_;
}

}  // namespace obscura::gpu
