#include "gpu/frame_backend.h"

#include "gpu/vulkan_functions.h"

#include <algorithm>
#include <cstring>

namespace obscura::gpu {
namespace {

bool samePlacements(const std::vector<TransientMemory::Placement>& a,
                    const std::vector<TransientMemory::Placement>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
        return x.heap == y.heap && x.offset == y.offset && x.size == y.size;
    });
}

bool sameHeaps(const std::vector<TransientMemory::Heap>& a, const std::vector<TransientMemory::Heap>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
        return x.size == y.size && x.alignment == y.alignment && x.memoryTypeBits == y.memoryTypeBits;
    });
}

}  // namespace

DeviceFrameBackend::DeviceFrameBackend(Device& device)
    : device_(device),
      pipelines_(std::make_unique<PipelineCache>(device)),
      timestamps_(std::make_unique<Timestamps>(device)) {}

DeviceFrameBackend::~DeviceFrameBackend() { waitIdle(); }

void DeviceFrameBackend::waitIdle() { vkDeviceWaitIdle(device_.vk()); }

ImagePtr DeviceFrameBackend::createTexture(const ImageDesc& desc, const void* texels, VkDeviceSize size,
                                           const std::string& name) {
    return device_.createTextureWithData(desc, texels, size, name.c_str());
}

BufferPtr DeviceFrameBackend::createBufferWithData(const void* data, VkDeviceSize size, VkBufferUsageFlags usage,
                                                   const std::string& name) {
    return device_.createBufferWithData(data, size, usage, name.c_str());
}

BufferPtr DeviceFrameBackend::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
                                           const std::string& name) {
    return device_.createBuffer(size, usage, memory, name.c_str());
}

ImagePtr DeviceFrameBackend::createImage(const ImageDesc& desc, const std::string& name) {
    return device_.createImage(desc, name.c_str());
}

BufferPtr DeviceFrameBackend::createFrameBuffer(VkDeviceSize size, VkBufferUsageFlags usage, const std::string& name) {
    return device_.createFrameBuffer(size, usage, name.c_str());
}

std::vector<ImagePtr> DeviceFrameBackend::transientImages(const TransientMemory& memory,
                                                          const std::vector<ImageDesc>& descs,
                                                          const std::vector<std::string>& names) {
    if (descs == transients_.descs && samePlacements(memory.placements, transients_.placements) &&
        sameHeaps(memory.heaps, transients_.plannedHeaps))
        return transients_.images;
    // Another plan: the last one's images are retired once the GPU is done (it is: each frame is
    // waited for); their memory is kept for the new ones where it is large enough.
    MemoryCategoryScope frameTargets(MemoryCategory::FrameTargets);
    std::vector<ImageMemoryPtr> heaps;
    std::vector<TransientMemory::Heap> kept;
    for (size_t h = 0; h < memory.heaps.size(); ++h) {
        const TransientMemory::Heap& need = memory.heaps[h];
        const bool fits = h < transients_.memory.size() &&
                          transients_.heaps[h].memoryTypeBits == need.memoryTypeBits &&
                          transients_.heaps[h].size >= need.size && transients_.heaps[h].alignment >= need.alignment;
        kept.push_back(fits ? transients_.heaps[h] : need);
        heaps.push_back(fits ? transients_.memory[h]
                             : device_.allocateImageMemory({need.size, need.alignment, need.memoryTypeBits}));
    }
    std::vector<ImagePtr> images;
    for (size_t i = 0; i < memory.placements.size(); ++i) {
        const TransientMemory::Placement& p = memory.placements[i];
        images.push_back(device_.createImage(descs[i], names[i].c_str(), heaps[p.heap], p.offset));
    }
    transients_ = {descs, memory.placements, memory.heaps, kept, heaps, images};
    return images;
}

void DeviceFrameBackend::run(FrameGraph& graph) {
    graph.compile([this](const ImageDesc& desc) { return device_.imageMemoryRequirements(desc); });
    graph.realize(*this);
    device_.context().submitAndWait([&](VkCommandBuffer cmd) {
        timestamps_->reset(cmd);
        graph.execute(device_, *pipelines_, cmd, timestamps_.get());
        recorded_ = std::chrono::steady_clock::now();
    });
    graph.submitted();
    timings_ = timestamps_->resolve();
    device_.endFrame();
}

}  // namespace obscura::gpu
