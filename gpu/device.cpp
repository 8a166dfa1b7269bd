#include "gpu/device.h"

#include "gpu/vk_check.h"

#include <algorithm>
#include <cstring>

namespace obscura::gpu {

bool isDepthFormat(VkFormat f) {
    return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT ||
           f == VK_FORMAT_D16_UNORM;
}
bool hasStencil(VkFormat f) { return f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT; }
VkImageAspectFlags aspectsOf(VkFormat f) {
    if (!isDepthFormat(f)) return VK_IMAGE_ASPECT_COLOR_BIT;
    return VK_IMAGE_ASPECT_DEPTH_BIT | (hasStencil(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}

Device::Device(std::unique_ptr<Context> context, std::optional<std::filesystem::path> pipelineCacheFolder)
    : context_(std::move(context)) {
    memory_ = std::make_unique<MemoryAllocator>(context_->device(), context_->memoryProperties(), &context_->faults());
    pipelineCache_ = std::make_unique<PipelineDiskCache>(*context_, std::move(pipelineCacheFolder));
    if (context_->validationEnabled())
        setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetDeviceProcAddr(context_->device(), "vkSetDebugUtilsObjectNameEXT"));

    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.maxLod = VK_LOD_CLAMP_NONE;
    vkCheck(vkCreateSampler(vk(), &si, nullptr, &linearClamp_), "vkCreateSampler");
    si.magFilter = si.minFilter = VK_FILTER_NEAREST;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    vkCheck(vkCreateSampler(vk(), &si, nullptr, &nearestClamp_), "vkCreateSampler");

    const VkDescriptorPoolSize sizes[] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 768},  // per-frame records too: shaders/common/frame_data.glsl says why
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 512}, {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 512},
        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 256},
    };
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = 256;
    pi.poolSizeCount = static_cast<uint32_t>(std::size(sizes));
    pi.pPoolSizes = sizes;
    vkCheck(vkCreateDescriptorPool(vk(), &pi, nullptr, &descriptorPool_), "vkCreateDescriptorPool");
}

Device::~Device() {
    vkDeviceWaitIdle(vk());
    pendingUploads_.clear();
    endFrame();
    for (const RecycledBuffer& r : frameBuffers_) destroyBuffer(r.buffer);
    vkDestroyDescriptorPool(vk(), descriptorPool_, nullptr);
    vkDestroySampler(vk(), linearClamp_, nullptr);
    vkDestroySampler(vk(), nearestClamp_, nullptr);
    pipelineCache_.reset();
    memory_.reset();
}

void Device::setName(VkObjectType type, uint64_t handle, const char* name) {
    if (!setObjectName_ || !name) return;
    VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    ni.objectType = type;
    ni.objectHandle = handle;
    ni.pObjectName = name;
    setObjectName_(vk(), &ni);
}

void Device::retire(std::function<void()> destroy) { retired_.push_back(std::move(destroy)); }

void Device::endFrame() {
    auto retired = std::move(retired_);
    retired_.clear();
    for (auto& destroy : retired) destroy();
    recycleFrameBuffers();
    vkResetDescriptorPool(vk(), descriptorPool_, 0);
}

VkDescriptorSet Device::allocateDescriptorSet(VkDescriptorSetLayout layout) {
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = descriptorPool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    vkCheck(vkAllocateDescriptorSets(vk(), &ai, &set), "vkAllocateDescriptorSets");
    return set;
}

Buffer* Device::newBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memoryUsage,
                          const char* debugName) {
    auto* b = new Buffer();
    b->size = size;
    b->id = nextResourceId_++;
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = size;
    bi.usage = usage;
    bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    vkCheck(vkCreateBuffer(vk(), &bi, nullptr, &b->buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk(), b->buffer, &req);
    try {
        b->allocation = memory_->allocate(req, memoryUsage, ResourceTiling::Linear);
    } catch (...) {
        // Out of memory: the buffer without memory dies here, not with the device.
        vkDestroyBuffer(vk(), b->buffer, nullptr);
        delete b;
        throw;
    }
    vkCheck(vkBindBufferMemory(vk(), b->buffer, b->allocation.memory, b->allocation.offset), "vkBindBufferMemory");
    setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(b->buffer), debugName);
    return b;
}

void Device::destroyBuffer(Buffer* buffer) {
    vkDestroyBuffer(vk(), buffer->buffer, nullptr);
    memory_->free(buffer->allocation);
    delete buffer;
}

BufferPtr Device::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memoryUsage,
                               const char* debugName) {
    return BufferPtr(newBuffer(size, usage, memoryUsage, debugName),
                     [this](Buffer* p) { retire([this, p] { destroyBuffer(p); }); });
}

BufferPtr Device::createFrameBuffer(VkDeviceSize size, VkBufferUsageFlags usage, const char* debugName) {
    // Same size and usage only: a shader may take an array's length from the buffer's range.
    Buffer* buffer = nullptr;
    const auto match = std::find_if(frameBuffers_.begin(), frameBuffers_.end(), [&](const RecycledBuffer& r) {
        return r.buffer->size == size && r.usage == usage;
    });
    if (match != frameBuffers_.end()) {
        buffer = match->buffer;
        buffer->id = nextResourceId_++;
        frameBuffers_.erase(match);
        setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(buffer->buffer), debugName);
    } else {
        buffer = newBuffer(size, usage, MemoryUsage::Upload, debugName);
    }
    // The GPU may read it until the frame ends: it is free again only after endFrame().
    return BufferPtr(buffer, [this, usage](Buffer* p) { releasedFrameBuffers_.push_back({p, usage, 0}); });
}

void Device::recycleFrameBuffers() {
    // A buffer no frame asked for within this many frames belongs to a scene that changed size.
    constexpr int kMaxIdleFrames = 4;
    std::erase_if(frameBuffers_, [&](RecycledBuffer& r) {
        if (++r.idleFrames <= kMaxIdleFrames) return false;
        destroyBuffer(r.buffer);
        return true;
    });
    frameBuffers_.insert(frameBuffers_.end(), releasedFrameBuffers_.begin(), releasedFrameBuffers_.end());
    releasedFrameBuffers_.clear();
}

namespace {

// The UNORM format an sRGB storage image is written through; VK_FORMAT_UNDEFINED for the others.
VkFormat storageAlias(const ImageDesc& desc) {
    if (!(desc.usage & VK_IMAGE_USAGE_STORAGE_BIT)) return VK_FORMAT_UNDEFINED;
    switch (desc.format) {
        case VK_FORMAT_R8G8B8A8_SRGB: return VK_FORMAT_R8G8B8A8_UNORM;
        case VK_FORMAT_B8G8R8A8_SRGB: return VK_FORMAT_B8G8R8A8_UNORM;
        default: return VK_FORMAT_UNDEFINED;
    }
}

VkImageCreateInfo imageCreateInfo(const ImageDesc& desc) {
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    // Storage through another format's view: the usage need only hold for a view that takes it.
    if (storageAlias(desc) != VK_FORMAT_UNDEFINED)
        ii.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
    if (desc.sampledAs != VK_FORMAT_UNDEFINED) ii.flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    ii.imageType = desc.depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    ii.format = desc.format;
    ii.extent = {desc.width, desc.height, desc.depth};
    ii.mipLevels = desc.mipLevels;
    ii.arrayLayers = 1;
    ii.samples = desc.samples;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = desc.usage;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    return ii;
}

}  // namespace

VkMemoryRequirements Device::imageMemoryRequirements(const ImageDesc& desc) const {
    VkImageCreateInfo ii = imageCreateInfo(desc);
    VkDeviceImageMemoryRequirements info{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
    info.pCreateInfo = &ii;
    VkMemoryRequirements2 requirements{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    vkGetDeviceImageMemoryRequirements(vk(), &info, &requirements);
    return requirements.memoryRequirements;
}

ImageMemoryPtr Device::allocateImageMemory(const VkMemoryRequirements& requirements) {
    auto* memory = new Allocation(memory_->allocate(requirements, MemoryUsage::DeviceLocal, ResourceTiling::Optimal));
    // Only the images placed in it hold it, and they are retired after the GPU is done with them.
    return ImageMemoryPtr(memory, [this](const Allocation* a) {
        memory_->free(*a);
        delete a;
    });
}

ImagePtr Device::createImage(const ImageDesc& desc, const char* debugName) {
    return createImage(desc, debugName, nullptr, 0);
}

ImagePtr Device::createImage(const ImageDesc& desc, const char* debugName, ImageMemoryPtr memory,
                             VkDeviceSize offset) {
    auto* img = new Image();
    img->desc = desc;
    img->id = nextResourceId_++;
    VkImageCreateInfo ii = imageCreateInfo(desc);
    vkCheck(vkCreateImage(vk(), &ii, nullptr, &img->image), "vkCreateImage");
    if (memory) {
        img->placedIn = std::move(memory);
    } else {
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(vk(), img->image, &req);
        try {
            img->allocation = memory_->allocate(req, MemoryUsage::DeviceLocal, ResourceTiling::Optimal);
        } catch (...) {
            vkDestroyImage(vk(), img->image, nullptr);
            delete img;
            throw;
        }
    }
    const Allocation& bound = img->placedIn ? *img->placedIn : img->allocation;
    vkCheck(vkBindImageMemory(vk(), img->image, bound.memory, bound.offset + offset), "vkBindImageMemory");
    setName(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(img->image), debugName);

    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = img->image;
    vi.viewType = desc.depth > 1 ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    vi.format = desc.format;
    // A depth/stencil view for sampling must name one aspect; attachments use the same view
    // (dynamic rendering accepts a depth-only view of a depth/stencil image for both aspects).
    vi.subresourceRange = {isDepthFormat(desc.format) ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT)
                                                      : VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT),
                           0, desc.mipLevels, 0, 1};
    const VkFormat alias = storageAlias(desc);
    // The sRGB view samples and attaches; storage is its alias's.
    VkImageViewUsageCreateInfo viewUsage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    viewUsage.usage = desc.usage & ~VkImageUsageFlags(VK_IMAGE_USAGE_STORAGE_BIT);
    if (alias != VK_FORMAT_UNDEFINED) vi.pNext = &viewUsage;
    if (desc.sampledAs != VK_FORMAT_UNDEFINED) vi.format = desc.sampledAs;
    vkCheck(vkCreateImageView(vk(), &vi, nullptr, &img->view), "vkCreateImageView");
    vi.format = desc.format;
    vi.pNext = nullptr;
    if (alias != VK_FORMAT_UNDEFINED) {
        vi.format = alias;
        vkCheck(vkCreateImageView(vk(), &vi, nullptr, &img->storageView), "vkCreateImageView");
        vi.format = desc.format;
    }
    if (hasStencil(desc.format)) {
        vi.subresourceRange.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
        vkCheck(vkCreateImageView(vk(), &vi, nullptr, &img->stencilView), "vkCreateImageView");
    }
    if ((desc.usage & VK_IMAGE_USAGE_STORAGE_BIT) && desc.mipLevels > 1) {
        for (uint32_t level = 0; level < desc.mipLevels; ++level) {
            vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1};
            vkCheck(vkCreateImageView(vk(), &vi, nullptr, &img->levelViews.emplace_back()), "vkCreateImageView");
        }
    }
    return ImagePtr(img, [this](Image* p) {
        retire([this, p] {
            vkDestroyImageView(vk(), p->view, nullptr);
            for (VkImageView level : p->levelViews) vkDestroyImageView(vk(), level, nullptr);
            if (p->stencilView) vkDestroyImageView(vk(), p->stencilView, nullptr);
            if (p->storageView) vkDestroyImageView(vk(), p->storageView, nullptr);
            vkDestroyImage(vk(), p->image, nullptr);
            memory_->free(p->allocation);
            delete p;  // the last image placed in a memory frees it
        });
    });
}

BufferPtr Device::createBufferWithData(const void* data, VkDeviceSize size, VkBufferUsageFlags usage,
                                       const char* debugName) {
    if (size == 0) size = 4;  // zero-sized buffers are invalid; keep one word
    auto buffer = createBuffer(size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::DeviceLocal, debugName);
    // Where the device's own memory is the host's too, mapped and coherent (lavapipe, integrated
    // GPUs), the contents are written in place: no staging copy of the whole scene waits for the
    // flush, and the GPU copies nothing.
    void* target = buffer->allocation.flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT ? buffer->mapped() : nullptr;
    if (!target) {
        auto staging = createBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
        target = staging->mapped();
        pendingUploads_.push_back({std::move(staging), buffer, size});
    }
    if (data) std::memcpy(target, data, size);
    else std::memset(target, 0, size);
    return buffer;
}

void Device::flushUploads() {
    if (pendingUploads_.empty()) return;
    context_->submitAndWait([&](VkCommandBuffer cmd) {
        for (const auto& u : pendingUploads_) {
            VkBufferCopy region{0, 0, u.size};
            vkCmdCopyBuffer(cmd, u.staging->buffer, u.destination->buffer, 1, &region);
        }
    });
    pendingUploads_.clear();
}

ImagePtr Device::createTextureWithData(const ImageDesc& descIn, const void* pixels, VkDeviceSize size,
                                       const char* debugName) {
    ImageDesc desc = descIn;
    desc.usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    auto image = createImage(desc, debugName);
    auto staging = createBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
    std::memcpy(staging->mapped(), pixels, size);
    context_->submitAndWait([&](VkCommandBuffer cmd) {
        VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
        b.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        b.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image->image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, desc.mipLevels, 0, 1};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 1;
        dep.pImageMemoryBarriers = &b;
        vkCmdPipelineBarrier2(cmd, &dep);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {desc.width, desc.height, desc.depth};
        vkCmdCopyBufferToImage(cmd, staging->buffer, image->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        b.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        vkCmdPipelineBarrier2(cmd, &dep);
    });
    image->layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    return image;
}

}  // namespace obscura::gpu
