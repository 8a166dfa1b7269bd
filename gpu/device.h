// The GPU device a delegate renders with: context, memory, buffers and images with deferred
// destruction (objects die at the end of the frame that last used them), samplers and the
// per-frame descriptor pool.
#pragma once

#include "gpu/context.h"
#include "gpu/memory.h"
#include "gpu/pipeline_disk_cache.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace obscura::gpu {

class Device;

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    Allocation allocation;
    VkDeviceSize size = 0;
    // Unique for the device's lifetime, and new each time a frame buffer is handed out: what a
    // cache keys on to know the contents are the same (handles and addresses are reused).
    uint64_t id = 0;
    void* mapped() const { return allocation.mapped; }
};

struct ImageDesc {
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t depth = 1;  // > 1: a 3D image (colour lookup tables)
    uint32_t mipLevels = 1;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    VkImageUsageFlags usage = 0;
    // The format `view` reads the texels as, where not `format`: an sRGB texture sampled through
    // its UNORM twin is filtered in its encoded values (the shader decodes), while uploads and mip
    // blits, which go through the image's own format, still filter in linear light.
    VkFormat sampledAs = VK_FORMAT_UNDEFINED;
    bool operator==(const ImageDesc&) const = default;
};

// Device memory that images are placed in side by side or over each other (the frame graph's
// transient images whose lifetimes do not overlap); freed with the last image placed in it.
using ImageMemoryPtr = std::shared_ptr<const Allocation>;

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;         // all aspects a shader may read (depth only for D/S)
    VkImageView stencilView = VK_NULL_HANDLE;  // stencil aspect of depth/stencil formats
    // An sRGB storage image's UNORM alias, for imageStore: no device offers storage on sRGB formats,
    // so shaders write encoded values through it while samplers decode through `view`.
    VkImageView storageView = VK_NULL_HANDLE;
    // Storage images with mips: one view per level (a storage descriptor names a single level).
    std::vector<VkImageView> levelViews;
    Allocation allocation;       // its own memory, unless placed in `placedIn`
    ImageMemoryPtr placedIn;
    ImageDesc desc;
    uint64_t id = 0;  // as Buffer::id
    // Between frames: the layout the last submitted work leaves it in (the frame graph starts from
    // it and keeps it; uploads leave textures SHADER_READ_ONLY_OPTIMAL).
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

using BufferPtr = std::shared_ptr<Buffer>;
using ImagePtr = std::shared_ptr<Image>;

bool isDepthFormat(VkFormat format);
bool hasStencil(VkFormat format);
VkImageAspectFlags aspectsOf(VkFormat format);

class Device {
public:
    // `pipelineCacheFolder`: where compiled pipelines are kept between processes
    // (gpu/pipeline_disk_cache.h); nullopt keeps them in memory only.
    explicit Device(std::unique_ptr<Context> context,
                    std::optional<std::filesystem::path> pipelineCacheFolder = std::nullopt);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    Context& context() { return *context_; }
    VkDevice vk() const { return context_->device(); }
    MemoryAllocator& memory() { return *memory_; }
    // Every pipeline is created through it.
    VkPipelineCache pipelineCache() const { return pipelineCache_->vk(); }
    // A Buffer::id / Image::id for a resource made outside this class (gpu/external_memory.h).
    uint64_t newResourceId() { return nextResourceId_++; }

    // Resources are shared_ptrs whose deleter queues destruction to the end of the frame.
    BufferPtr createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memoryUsage,
                           const char* debugName);
    // A host-visible buffer for one frame's records (camera, instances, pass constants). A frame
    // asks for the same sizes as the last one, so these are recycled instead of created: released
    // buffers come back at the end of the frame and one not asked for again within a few frames
    // is destroyed. The steady state of an unchanged scene allocates nothing, and memory stays
    // bounded while sizes change.
    BufferPtr createFrameBuffer(VkDeviceSize size, VkBufferUsageFlags usage, const char* debugName);
    ImagePtr createImage(const ImageDesc& desc, const char* debugName);
    // What an image of `desc` asks of memory, without making one.
    VkMemoryRequirements imageMemoryRequirements(const ImageDesc& desc) const;
    ImageMemoryPtr allocateImageMemory(const VkMemoryRequirements& requirements);
    // An image at `offset` of `memory`, which other images may share at other times.
    ImagePtr createImage(const ImageDesc& desc, const char* debugName, ImageMemoryPtr memory, VkDeviceSize offset);
    // A device-local buffer whose contents arrive with the next flushUploads(): sync creates
    // many, and all their copies go to the GPU in one submission (or none, where the buffer's
    // memory is mapped: written at once).
    BufferPtr createBufferWithData(const void* data, VkDeviceSize size, VkBufferUsageFlags usage,
                                   const char* debugName);
    void flushUploads();
    // Upload pixel data (tightly packed, mip 0) and leave the image SHADER_READ_ONLY_OPTIMAL.
    ImagePtr createTextureWithData(const ImageDesc& desc, const void* pixels, VkDeviceSize size,
                                   const char* debugName);

    VkSampler linearClampSampler() const { return linearClamp_; }
    VkSampler nearestClampSampler() const { return nearestClamp_; }

    // Per-frame descriptor sets, freed all at once when the frame ends.
    VkDescriptorSet allocateDescriptorSet(VkDescriptorSetLayout layout);

    // The frame ends: the GPU is idle, retired objects die and descriptor sets are recycled.
    void endFrame();
    void retire(std::function<void()> destroy);

private:
    void setName(VkObjectType type, uint64_t handle, const char* name);
    Buffer* newBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memoryUsage, const char* debugName);
    void destroyBuffer(Buffer* buffer);
    void recycleFrameBuffers();

    std::unique_ptr<Context> context_;
    std::unique_ptr<MemoryAllocator> memory_;
    std::unique_ptr<PipelineDiskCache> pipelineCache_;
    std::vector<std::function<void()>> retired_;
    uint64_t nextResourceId_ = 1;
    struct PendingUpload {
        BufferPtr staging;
        BufferPtr destination;
        VkDeviceSize size;
    };
    std::vector<PendingUpload> pendingUploads_;
    struct RecycledBuffer {
        Buffer* buffer;
        VkBufferUsageFlags usage;
        int idleFrames;  // frames ended since it was last released
    };
    std::vector<RecycledBuffer> frameBuffers_;          // free for this frame
    std::vector<RecycledBuffer> releasedFrameBuffers_;  // released during this frame: free after it
    VkSampler linearClamp_ = VK_NULL_HANDLE;
    VkSampler nearestClamp_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
};

}  // namespace obscura::gpu
