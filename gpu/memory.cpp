#include "gpu/memory.h"

#include "gpu/vk_check.h"

#include <algorithm>

namespace obscura::gpu {
namespace {
VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }
}  // namespace

MemoryAllocator::MemoryAllocator(VkDevice device, const VkPhysicalDeviceMemoryProperties& properties,
                                 const FaultInjection* faults)
    : device_(device), properties_(properties), faults_(faults) {}

MemoryAllocator::~MemoryAllocator() {
    for (auto& b : blocks_)
        if (b->memory) vkFreeMemory(device_, b->memory, nullptr);
}

VkDeviceSize MemoryAllocator::bytesReserved() const {
    VkDeviceSize total = 0;
    for (auto& b : blocks_) total += b->size;
    return total;
}

uint32_t MemoryAllocator::findMemoryType(uint32_t typeBits, MemoryUsage usage) const {
    VkMemoryPropertyFlags required = 0, preferred = 0;
    switch (usage) {
        case MemoryUsage::DeviceLocal: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
        case MemoryUsage::Upload:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            break;
        case MemoryUsage::Readback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            // Cached memory makes the host's reads of the readback fast.
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
    }
    uint32_t fallback = UINT32_MAX;
    for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        VkMemoryPropertyFlags f = properties_.memoryTypes[i].propertyFlags;
        if ((f & required) != required) continue;
        if ((f & preferred) == preferred) return i;
        if (fallback == UINT32_MAX) fallback = i;
    }
    if (fallback == UINT32_MAX) throw DeviceError("no Vulkan memory type fits the resource");
    return fallback;
}

void MemoryAllocator::Block::addRange(VkDeviceSize offset, VkDeviceSize rangeSize) {
    freeRanges[offset] = rangeSize;
    bySize.insert({rangeSize, offset});
}

void MemoryAllocator::Block::removeRange(std::map<VkDeviceSize, VkDeviceSize>::iterator it) {
    bySize.erase({it->second, it->first});
    freeRanges.erase(it);
}

bool MemoryAllocator::tryPlace(Block& block, const VkMemoryRequirements& req, VkDeviceSize* offset) {
    // Best fit: the smallest ranges that can hold the request; a range of size + alignment - 1
    // always can, smaller ones only if their start happens to be aligned.
    for (auto candidate = block.bySize.lower_bound({req.size, 0}); candidate != block.bySize.end(); ++candidate) {
        VkDeviceSize rangeStart = candidate->second, rangeSize = candidate->first;
        VkDeviceSize start = alignUp(rangeStart, req.alignment);
        VkDeviceSize end = rangeStart + rangeSize;
        if (start + req.size > end) continue;
        block.removeRange(block.freeRanges.find(rangeStart));
        if (start > rangeStart) block.addRange(rangeStart, start - rangeStart);
        if (start + req.size < end) block.addRange(start + req.size, end - (start + req.size));
        *offset = start;
        return true;
    }
    return false;
}

thread_local MemoryCategory currentCategory = MemoryCategory::Other;

MemoryCategoryScope::MemoryCategoryScope(MemoryCategory category) : previous_(currentCategory) {
    currentCategory = category;
}

MemoryCategoryScope::~MemoryCategoryScope() { currentCategory = previous_; }

MemoryCategory MemoryCategoryScope::current() { return currentCategory; }

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& req, MemoryUsage usage, ResourceTiling tiling) {
    if (faults_ && faults_->strikes(FaultInjection::Kind::OutOfMemory))
        vkCheck(VK_ERROR_OUT_OF_DEVICE_MEMORY, "device memory allocation (OBSCURA_FAULT_INJECTION)");
    uint32_t type = findMemoryType(req.memoryTypeBits, usage);
    Allocation a;
    for (uint32_t i = 0; i < blocks_.size(); ++i) {
        Block& b = *blocks_[i];
        if (b.memoryType != type || b.tiling != tiling) continue;
        if (tryPlace(b, req, &a.offset)) {
            a.block = i;
            break;
        }
    }
    if (a.block == UINT32_MAX) {
        auto block = std::make_unique<Block>();
        block->size = std::max(kBlockSize, alignUp(req.size, 1u << 20));
        block->memoryType = type;
        block->tiling = tiling;
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = block->size;
        ai.memoryTypeIndex = type;
        vkCheck(vkAllocateMemory(device_, &ai, nullptr, &block->memory), "vkAllocateMemory");
        if (properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
            vkCheck(vkMapMemory(device_, block->memory, 0, VK_WHOLE_SIZE, 0, &block->mapped), "vkMapMemory");
        block->addRange(0, block->size);
        if (!tryPlace(*block, req, &a.offset)) throw DeviceError("allocation larger than its own block");
        blocks_.push_back(std::move(block));
        a.block = static_cast<uint32_t>(blocks_.size() - 1);
    }
    Block& b = *blocks_[a.block];
    a.memory = b.memory;
    a.size = req.size;
    a.mapped = b.mapped ? static_cast<char*>(b.mapped) + a.offset : nullptr;
    a.flags = properties_.memoryTypes[b.memoryType].propertyFlags;
    a.tiling = tiling;
    a.category = MemoryCategoryScope::current();
    b.used += req.size;
    inUse_ += req.size;
    inUseByTiling_[size_t(a.tiling)] += a.size;
    inUseByCategory_[size_t(a.category)] += a.size;
    return a;
}

void MemoryAllocator::free(const Allocation& a) {
    if (!a) return;
    Block& b = *blocks_.at(a.block);
    b.used -= a.size;
    inUse_ -= a.size;
    inUseByTiling_[size_t(a.tiling)] -= a.size;
    inUseByCategory_[size_t(a.category)] -= a.size;
    // Coalesce with the preceding and the following free range.
    VkDeviceSize offset = a.offset, size = a.size;
    auto next = b.freeRanges.lower_bound(offset);
    if (next != b.freeRanges.begin()) {
        auto prev = std::prev(next);
        if (prev->first + prev->second == offset) {
            offset = prev->first;
            size += prev->second;
            b.removeRange(prev);
        }
    }
    if (next != b.freeRanges.end() && a.offset + a.size == next->first) {
        size += next->second;
        b.removeRange(next);
    }
    b.addRange(offset, size);
}

}  // namespace obscura::gpu
