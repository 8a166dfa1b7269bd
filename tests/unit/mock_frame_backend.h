// A frame backend without a GPU: images and buffers are descriptions (buffers with host memory
// behind them), and a frame graph is compiled, given its resources and "submitted" without
// recording a command. Each frame's compiled passes are kept for the test to read.
#pragma once

#include "gpu/frame_backend.h"

#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace obscura::test {

class MockFrameBackend final : public gpu::FrameBackend {
public:
    struct Frame {
        std::vector<gpu::FrameGraph::CompiledPass> passes;
        std::vector<std::string> imageNames;  // by image index
        std::vector<std::string> bufferNames;  // by buffer index
        gpu::TransientMemory memory;
    };

    gpu::ImagePtr createTexture(const gpu::ImageDesc& desc, const void*, VkDeviceSize, const std::string&) override {
        gpu::ImagePtr image = createImage(desc, {});
        image->desc.usage |= VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        image->layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        return image;
    }
    gpu::BufferPtr createBufferWithData(const void* data, VkDeviceSize size, VkBufferUsageFlags,
                                        const std::string&) override {
        gpu::BufferPtr buffer = hostBuffer(size);
        if (data) std::memcpy(buffer->mapped(), data, size);
        return buffer;
    }
    gpu::BufferPtr createBuffer(VkDeviceSize size, VkBufferUsageFlags, gpu::MemoryUsage, const std::string&) override {
        return hostBuffer(size);
    }
    gpu::ImagePtr createImage(const gpu::ImageDesc& desc, const std::string&) override {
        auto image = std::make_shared<gpu::Image>();
        image->desc = desc;
        image->id = ++ids_;
        return image;
    }
    std::vector<gpu::ImagePtr> transientImages(const gpu::TransientMemory&, const std::vector<gpu::ImageDesc>& descs,
                                               const std::vector<std::string>& names) override {
        std::vector<gpu::ImagePtr> images;
        for (size_t i = 0; i < descs.size(); ++i) images.push_back(createImage(descs[i], names[i]));
        return images;
    }
    gpu::BufferPtr createFrameBuffer(VkDeviceSize size, VkBufferUsageFlags, const std::string&) override {
        return hostBuffer(size);
    }
    void run(gpu::FrameGraph& graph) override {
        graph.compile();
        graph.realize(*this);
        Frame frame{graph.compiled(), {}, {}, graph.transientMemory()};
        for (uint32_t i = 0; i < graph.imageCount(); ++i) frame.imageNames.push_back(graph.imageName(i));
        for (uint32_t i = 0; i < graph.bufferCount(); ++i) frame.bufferNames.push_back(graph.bufferName(i));
        frames.push_back(std::move(frame));
        graph.submitted();
    }
    std::vector<gpu::PassTime> timings() override { return {}; }
    std::chrono::steady_clock::time_point recorded() const override { return {}; }
    void waitIdle() override {}

    std::vector<Frame> frames;  // every graph run, in order

private:
    gpu::BufferPtr hostBuffer(VkDeviceSize size) {
        auto memory = std::make_shared<std::vector<std::byte>>(size);
        auto buffer = std::shared_ptr<gpu::Buffer>(new gpu::Buffer(), [memory](gpu::Buffer* b) { delete b; });
        buffer->size = size;
        buffer->id = ++ids_;
        buffer->allocation.mapped = memory->data();
        return buffer;
    }
    uint64_t ids_ = 0;
};

}  // namespace obscura::test
