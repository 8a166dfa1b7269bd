// Sub-allocation of device memory: a few large VkDeviceMemory blocks per memory type, carved
// best-fit from free ranges indexed by size (O(log n) per allocation with tens of thousands of
// live resources) and coalesced on free. Buffers (linear) and images (optimal tiling)
// use separate blocks so bufferImageGranularity never matters. Host-visible blocks stay mapped.
#pragma once

#include "gpu/fault_injection.h"

#include "gpu/vulkan_functions.h"

#include <cstdint>
#include <map>
#include <set>
#include <memory>
#include <vector>

namespace obscura::gpu {

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr;     // host pointer at `offset` for host-visible memory
    uint32_t block = UINT32_MAX;
    VkMemoryPropertyFlags flags = 0;  // of the memory type it lives in
    explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

enum class MemoryUsage {
    DeviceLocal,   // GPU only
    Upload,        // host writes, GPU reads (staging, per-frame constants)
    Readback       // GPU writes, host reads (AOV readback)
};

enum class ResourceTiling { Linear, Optimal };

class MemoryAllocator {
public:
    // `faults` (may be null) can make allocations fail on cue.
    MemoryAllocator(VkDevice device, const VkPhysicalDeviceMemoryProperties& properties,
                    const FaultInjection* faults = nullptr);
    ~MemoryAllocator();
    MemoryAllocator(const MemoryAllocator&) = delete;
    MemoryAllocator& operator=(const MemoryAllocator&) = delete;

    // Throws DeviceError when no memory type fits or the device is out of memory.
    Allocation allocate(const VkMemoryRequirements& requirements, MemoryUsage usage, ResourceTiling tiling);
    void free(const Allocation& allocation);

    VkDeviceSize bytesInUse() const { return inUse_; }
    VkDeviceSize bytesReserved() const;
    size_t blockCount() const { return blocks_.size(); }

    static constexpr VkDeviceSize kBlockSize = 64ull << 20;

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        VkDeviceSize size = 0;
        uint32_t memoryType = 0;
        ResourceTiling tiling = ResourceTiling::Linear;
        void* mapped = nullptr;
        std::map<VkDeviceSize, VkDeviceSize> freeRanges;  // offset -> size
        std::set<std::pair<VkDeviceSize, VkDeviceSize>> bySize;  // (size, offset) of the same ranges
        void addRange(VkDeviceSize offset, VkDeviceSize size);
        void removeRange(std::map<VkDeviceSize, VkDeviceSize>::iterator it);
        VkDeviceSize used = 0;
    };
    uint32_t findMemoryType(uint32_t typeBits, MemoryUsage usage) const;
    bool tryPlace(Block& block, const VkMemoryRequirements& req, VkDeviceSize* offset);

    VkDevice device_;
    VkPhysicalDeviceMemoryProperties properties_;
    const FaultInjection* faults_;
    std::vector<std::unique_ptr<Block>> blocks_;
    VkDeviceSize inUse_ = 0;
};

}  // namespace obscura::gpu
