// Images kept from frame to frame (STYLE.md "Explicit history"). Their owner keeps these objects;
// the frame graph that imports one makes its image when there is none or its description changed
// (a resize), and the image keeps the layout the last frame left it in (Image::layout), so no
// owner carries a layout or a flag for it.
#pragma once

#include "gpu/device.h"

#include <array>

namespace obscura::gpu {

// One image kept from frame to frame: the shadow atlas, the reference's running sum, the
// environment maps.
class PersistentImage {
public:
    const ImagePtr& image() const { return image_; }
    // A frame has written it since it was made: it holds what that frame left.
    bool holdsContents() const { return written_; }

private:
    friend class FrameGraph;
    ImagePtr image_;
    bool written_ = false;
};

// A history (Granite's history input): two images that swap roles each frame; the frame reads the
// one the last frame wrote and writes the other (FrameGraph::addHistory).
class HistoryImages {
private:
    friend class FrameGraph;
    std::array<PersistentImage, 2> images_;
    uint32_t current_ = 0;  // the image the last frame wrote
};

}  // namespace obscura::gpu
