// What the frame asks of a GPU, behind one interface: the resources that outlive a frame, and
// running a frame graph. DeviceFrameBackend runs frames on a Vulkan device; the unit tests run
// whole frames, wired by the renderer, against a mock (tests/unit/frame_wiring_test.cpp).
#pragma once

#include "gpu/frame_graph.h"
#include "gpu/timestamps.h"

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace obscura::gpu {

class FrameBackend {
public:
    virtual ~FrameBackend() = default;

    // A read-only texture from `texels` (tightly packed, mip 0).
    virtual ImagePtr createTexture(const ImageDesc& desc, const void* texels, VkDeviceSize size,
                                   const std::string& name) = 0;
    // A device-local buffer holding `data` (zeros when null) once the uploads are flushed.
    virtual BufferPtr createBufferWithData(const void* data, VkDeviceSize size, VkBufferUsageFlags usage,
                                           const std::string& name) = 0;
    virtual BufferPtr createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
                                   const std::string& name) = 0;

    // What FrameGraph::realize() makes: an image kept from frame to frame, this frame's transient
    // images (at the places `memory` gives them), and a buffer for this frame's constants.
    virtual ImagePtr createImage(const ImageDesc& desc, const std::string& name) = 0;
    virtual std::vector<ImagePtr> transientImages(const TransientMemory& memory, const std::vector<ImageDesc>& descs,
                                                  const std::vector<std::string>& names) = 0;
    virtual BufferPtr createFrameBuffer(VkDeviceSize size, VkBufferUsageFlags usage, const std::string& name) = 0;

    // Compiles `graph`, makes what it needs, records and submits it, and waits for it.
    virtual void run(FrameGraph& graph) = 0;
    // The last frame's passes and their GPU times, and when its commands were recorded.
    virtual std::vector<PassTime> timings() = 0;
    virtual std::chrono::steady_clock::time_point recorded() const = 0;
    // The GPU is idle: nothing recorded is still running.
    virtual void waitIdle() = 0;
};

class DeviceFrameBackend final : public FrameBackend {
public:
    explicit DeviceFrameBackend(Device& device);
    ~DeviceFrameBackend() override;

    Device& device() { return device_; }

    ImagePtr createTexture(const ImageDesc& desc, const void* texels, VkDeviceSize size,
                           const std::string& name) override;
    BufferPtr createBufferWithData(const void* data, VkDeviceSize size, VkBufferUsageFlags usage,
                                   const std::string& name) override;
    BufferPtr createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
                           const std::string& name) override;
    ImagePtr createImage(const ImageDesc& desc, const std::string& name) override;
    std::vector<ImagePtr> transientImages(const TransientMemory& memory, const std::vector<ImageDesc>& descs,
                                          const std::vector<std::string>& names) override;
    BufferPtr createFrameBuffer(VkDeviceSize size, VkBufferUsageFlags usage, const std::string& name) override;
    void run(FrameGraph& graph) override;
    std::vector<PassTime> timings() override { return timings_; }
    std::chrono::steady_clock::time_point recorded() const override { return recorded_; }
    void waitIdle() override;

private:
    Device& device_;
    std::unique_ptr<PipelineCache> pipelines_;
    std::unique_ptr<Timestamps> timestamps_;
    // The transient images of the last frames, kept while frames place the same images alike (a
    // steady frame allocates nothing); another plan makes them again, in the same memory where it
    // fits (the frames of a still, whose passes differ from its first frame's, share one heap).
    struct Transients {
        std::vector<ImageDesc> descs;
        std::vector<TransientMemory::Placement> placements;
        std::vector<TransientMemory::Heap> plannedHeaps;  // as the plan asked for them
        std::vector<TransientMemory::Heap> heaps;         // as allocated: at least as large
        std::vector<ImageMemoryPtr> memory;               // one per heap
        std::vector<ImagePtr> images;
    } transients_;
    std::vector<PassTime> timings_;
    std::chrono::steady_clock::time_point recorded_;
};

}  // namespace obscura::gpu
