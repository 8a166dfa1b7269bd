// Sub-allocation of device memory: a few large VkDeviceMemory blocks per memory type, carved
// best-fit from free ranges indexed by size (O(log n) per allocation with tens of thousands of
// live resources) and coalesced on free. Buffers (linear) and images (optimal tiling)
// use separate blocks so bufferImageGranularity never matters. Host-visible blocks stay mapped.
#pragma once

#include "gpu/fault_injection.h"

#include "gpu/vulkan_functions.h"

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <memory>
#include <vector>

namespace obscura::gpu {

enum class MemoryUsage {
    DeviceLocal,   // GPU only
    Upload,        // host writes, GPU reads (staging, per-frame constants)
    Readback       // GPU writes, host reads (AOV readback)
};

enum class ResourceTiling { Linear, Optimal };

// What memory holds, for the counts a host reads (ObscuraMemoryStats): set for the allocations of a
// scope (MemoryCategoryScope) by the code that owns the resources; anything else is Other.
enum class MemoryCategory : uint8_t {
    Other,          // per-frame records, staging, small buffers of the passes
    FrameTargets,   // the frame graph's transient images (aliased within a frame)
    FrameHistory,   // images kept from frame to frame: histories, shadow atlas, accumulation
    Textures,       // material textures (environment maps are the frame's history)
    Geometry,       // vertex and index data
    RenderBuffers,  // the AOVs' destinations and their device-local twins
    Count
};

// Allocations made on this thread while it lives count towards `category` (scopes nest).
class MemoryCategoryScope {
public:
    explicit MemoryCategoryScope(MemoryCategory category);
    ~MemoryCategoryScope();
    MemoryCategoryScope(const MemoryCategoryScope&) = delete;
    MemoryCategoryScope& operator=(const MemoryCategoryScope&) = delete;
    static MemoryCategory current();

private:
    MemoryCategory previous_;
};

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr;     // host pointer at `offset` for host-visible memory
    uint32_t block = UINT32_MAX;
    VkMemoryPropertyFlags flags = 0;  // of the memory type it lives in
    ResourceTiling tiling = ResourceTiling::Linear;
    MemoryCategory category = MemoryCategory::Other;
    explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

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
    // Of bytesInUse(): images (optimal tiling) or buffers; what a category holds.
    VkDeviceSize bytesInUse(ResourceTiling tiling) const { return inUseByTiling_[size_t(tiling)]; }
    VkDeviceSize bytesInUse(MemoryCategory category) const { return inUseByCategory_[size_t(category)]; }
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
    std::array<VkDeviceSize, 2> inUseByTiling_{};
    std::array<VkDeviceSize, size_t(MemoryCategory::Count)> inUseByCategory_{};
};

}  // namespace obscura::gpu
