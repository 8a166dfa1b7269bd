#include "delegate/prims/render_buffer.h"

#include "gpu/device.h"
#include "gpu/external_memory.h"

#include <cstring>

#include <unistd.h>

namespace obscura::delegate {

ObscuraFormat parseFormat(const std::string& t) {
    if (t == "float32Vec4") return OBSCURA_FORMAT_FLOAT32_VEC4;
    if (t == "float32Vec3") return OBSCURA_FORMAT_FLOAT32_VEC3;
    if (t == "float32") return OBSCURA_FORMAT_FLOAT32;
    if (t == "int32") return OBSCURA_FORMAT_INT32;
    if (t == "unorm8Vec4") return OBSCURA_FORMAT_UNORM8_VEC4;
    return OBSCURA_FORMAT_UNKNOWN;
}

size_t RenderBuffer::bytesPerPixel() const {
    switch (format_) {
        case OBSCURA_FORMAT_FLOAT32_VEC4: return 16;
        case OBSCURA_FORMAT_FLOAT32_VEC3: return 12;
        case OBSCURA_FORMAT_FLOAT32:
        case OBSCURA_FORMAT_INT32:
        case OBSCURA_FORMAT_UNORM8_VEC4: return 4;
        default: return 0;
    }
}

void RenderBuffer::pull(SceneAccess& s, ObscuraDirtyBits, SyncContext& ctx) {
    if (!s.anyDirty()) return;
    auto dims = s.getInt2("dimensions");
    // The frame's images are the buffer's size: the device's largest 2D image bounds it.
    const int64_t maxDimension = ctx.device.context().properties().limits.maxImageDimension2D;
    if (dims[0] <= 0 || dims[1] <= 0 || dims[0] > maxDimension || dims[1] > maxDimension)
        throw PrimDataError(s.path() + ": dimensions (" + std::to_string(dims[0]) + ", " + std::to_string(dims[1]) +
                            ") must be within 1.." + std::to_string(maxDimension) +
                            ", the device's largest image");
    ObscuraFormat f = parseFormat(s.getToken("format"));
    if (f == OBSCURA_FORMAT_UNKNOWN) throw PrimDataError(s.path() + ": unknown format");
    width_ = uint32_t(dims[0]);
    height_ = uint32_t(dims[1]);
    format_ = f;
    rendered_ = false;
}

const gpu::BufferPtr& RenderBuffer::storage(gpu::Device& device) {
    VkDeviceSize size = VkDeviceSize(width_) * height_ * bytesPerPixel();
    gpu::MemoryCategoryScope renderBuffers(gpu::MemoryCategory::RenderBuffers);
    if (!storage_ || storage_->size != size || storageExported_ != exported_) {
        // An importer reads an exported buffer as a storage buffer or copies from it.
        storage_ = exported_ ? gpu::createExportableBuffer(device, size,
                                                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                              VK_BUFFER_USAGE_TRANSFER_DST_BIT)
                             : device.createBuffer(size,
                                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                   gpu::MemoryUsage::Readback, path().c_str());
        storageExported_ = exported_;
    }
    return storage_;
}

const gpu::BufferPtr& RenderBuffer::deviceStaging(gpu::Device& device) {
    const gpu::BufferPtr& host = storage(device);
    gpu::MemoryCategoryScope renderBuffers(gpu::MemoryCategory::RenderBuffers);
    if (exported_ || (host->allocation.flags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) {
        staging_.reset();
    } else if (!staging_ || staging_->size != host->size) {
        staging_ = device.createBuffer(host->size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                       gpu::MemoryUsage::DeviceLocal, path().c_str());
    }
    return staging_;
}

void RenderBuffer::exportTo(gpu::Device& device, gpu::ExportTimeline& timeline, ObscuraExternalBuffer& out) {
    setExported();
    const gpu::BufferPtr& buffer = storage(device);
    gpu::ExportedMemory memory = gpu::exportMemory(device, *buffer);
    int semaphore = -1;
    try {
        semaphore = timeline.exportSemaphore();
    } catch (...) {
        close(memory.fd);
        throw;
    }
    out.width = width_;
    out.height = height_;
    out.format = format_;
    out.rowStride = width_ * bytesPerPixel();
    out.size = buffer->size;
    out.memoryFd = memory.fd;
    out.allocationSize = memory.allocationSize;
    out.memoryTypeIndex = memory.memoryTypeIndex;
    out.dedicated = memory.dedicated ? 1 : 0;
    out.semaphoreFd = semaphore;
    const gpu::ExternalHandleSupport& support = device.context().externalHandles();
    std::memcpy(out.deviceUUID, support.deviceUUID, sizeof(out.deviceUUID));
    std::memcpy(out.driverUUID, support.driverUUID, sizeof(out.driverUUID));
}

}  // namespace obscura::delegate
