// A render pass's AOV bindings resolved to the render buffers the frame writes: names checked, each
// AOV's format matched, one size for all, within what the device can make.
#pragma once

#include "delegate/prims/render_buffer.h"
#include "passes/aov_readback.h"

#include <obscura/obscura.h>

#include <functional>
#include <vector>

namespace obscura::delegate {

struct AovBindings {
    std::vector<passes::AovRequest> requests;
    std::vector<RenderBuffer*> targets;  // the buffers of `requests`, in the same order
    uint32_t width = 0, height = 0;      // the frame's size: the viewport's, else the buffers'
};

using RenderBufferLookup = std::function<RenderBuffer*(const char* path)>;

// Refuses (ApiError INVALID_STATE) a pass that binds a mapped buffer: a mapping keeps its contents
// until unmap, so this is checked before anything is pulled or drawn.
void refuseMappedBuffers(const ObscuraRenderPassDesc& desc, const RenderBufferLookup& find);

// Throws ApiError for a binding the host got wrong (unknown AOV or buffer, wrong format, sizes that
// differ, a size beyond `maxImageSize`). A render buffer with bad data is a skipped prim like any
// other: it is left out and the frame renders into the others.
AovBindings bindAovs(const ObscuraRenderPassDesc& desc, const RenderBufferLookup& find, gpu::Device& device,
                     uint32_t maxImageSize);

}  // namespace obscura::delegate
