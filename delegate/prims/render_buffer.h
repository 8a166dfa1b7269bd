// The render buffer bprim: an AOV's destination, in host-visible memory the host maps.
#pragma once

#include "delegate/prims/prim.h"
#include "gpu/device.h"
#include "gpu/external_memory.h"

namespace obscura::delegate {

class RenderBuffer final : public Prim {
public:
    using Prim::Prim;
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    ObscuraFormat format() const { return format_; }
    size_t bytesPerPixel() const;
    // (Re)allocates the storage when the size or format changed: host-visible memory the host
    // maps, or, once exported, exportable device memory the frame writes directly.
    const gpu::BufferPtr& storage(gpu::Device& device);
    // Where the GPU writes the AOV when the host-visible storage is not device-local (discrete
    // GPUs): shader writes go to video memory and one copy moves them to the host, instead of
    // every shader write crossing the bus. Null when the storage itself is device-local, and for an
    // exported buffer.
    const gpu::BufferPtr& deviceStaging(gpu::Device& device);
    // The ABI's display interop (exportRenderBuffer): from now on the storage is exportable device
    // memory, made again when the size or format changes.
    void setExported() { exported_ = true; }
    // Makes the storage exportable and describes it to the host: its memory's descriptor and the
    // frames' semaphore's (the caller checked that the device can export memory).
    void exportTo(gpu::Device& device, gpu::ExportTimeline& timeline, ObscuraExternalBuffer& out);
    bool exported() const { return exported_; }
    bool rendered() const { return rendered_; }
    void setRendered(bool r) { rendered_ = r; }
    bool mapped = false;

private:
    void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) override;
    uint32_t width_ = 0, height_ = 0;
    ObscuraFormat format_ = OBSCURA_FORMAT_FLOAT32_VEC4;
    gpu::BufferPtr storage_;
    gpu::BufferPtr staging_;
    bool rendered_ = false;
    bool exported_ = false;
    bool storageExported_ = false;  // what storage_ was made as
};

ObscuraFormat parseFormat(const std::string& token);

}  // namespace obscura::delegate
