#include "gpu/history_images.h"

namespace obscura::gpu {

bool HistoryImages::ensure(Device& device, const ImageDesc& desc, const char* debugName) {
    if (images_[0] && images_[0]->desc == desc) return false;
    for (uint32_t i = 0; i < 2; ++i) {
        images_[i] = device.createImage(desc, debugName);
        layouts_[i] = VK_IMAGE_LAYOUT_UNDEFINED;
    }
    return true;
}

HistoryImages::Imported HistoryImages::import(FrameGraph& graph, const std::string& name) {
    uint32_t previous = current_;
    current_ = 1 - current_;
    imported_[previous] = graph.importImage(name + ".previous", images_[previous], layouts_[previous]);
    imported_[current_] = graph.importImage(name, images_[current_], layouts_[current_]);
    graph.markOutput(imported_[current_]);
    return {imported_[previous], imported_[current_], layouts_[previous] != VK_IMAGE_LAYOUT_UNDEFINED};
}

void HistoryImages::keep(const FrameGraph& graph) {
    for (uint32_t i = 0; i < 2; ++i) layouts_[i] = graph.finalLayout(imported_[i]);
}

}  // namespace obscura::gpu
