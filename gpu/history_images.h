// Persistent ping-pong images for temporal passes (STYLE.md "Explicit history"): two images that
// outlive the frame; each frame reads the one the previous frame wrote and writes the other. The
// owner (the delegate) keeps the pair; each frame imports both into the frame graph and, once the
// graph is compiled, keeps the layouts the graph leaves them in for the next frame's import.
#pragma once

#include "gpu/frame_graph.h"

#include <array>
#include <string>

namespace obscura::gpu {

class HistoryImages {
public:
    // This frame's imports: last frame's image (to read) and this frame's (to write).
    struct Imported {
        ImageHandle previous;
        ImageHandle current;
        // Whether `previous` holds something: it was written since it was created. An image never
        // written is still imported (a binding needs a resource) but its contents are garbage.
        bool previousWritten;
    };

    // (Re)creates both images when `desc` differs from theirs (first use, resize); returns true
    // when it did: there is no history to read.
    bool ensure(Device& device, const ImageDesc& desc, const char* debugName);
    // Swaps the roles and imports both into `graph` as `name.previous` and `name`; the written
    // image is marked as a graph output, since the next frame reads it.
    Imported import(FrameGraph& graph, const std::string& name);
    // After graph.compile(): the layouts this frame leaves both images in.
    void keep(const FrameGraph& graph);

private:
    std::array<ImagePtr, 2> images_;
    std::array<VkImageLayout, 2> layouts_{VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED};
    std::array<ImageHandle, 2> imported_;
    uint32_t current_ = 0;  // the image the last import writes
};

}  // namespace obscura::gpu
