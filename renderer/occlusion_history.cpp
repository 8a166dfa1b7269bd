#include "renderer/occlusion_history.h"

#include "passes/coverage_buffer.h"

namespace obscura::renderer {

std::optional<CoverageBuffer> OcclusionHistory::reproject(const CoverageKey& key, const CoverageView& current) {
    pending_.reset();  // a frame that failed before frameDone wrote nothing that counts
    if (!valid_ || !(valid_->key == key) || valid_->view.width != current.width ||
        valid_->view.height != current.height)
        return std::nullopt;
    return CoverageBuffer(static_cast<const float*>(tiles_->mapped()), passes::kCoverageTilePixels, valid_->view,
                          current);
}

void OcclusionHistory::addToFrame(gpu::FrameGraph& graph, gpu::ImageHandle depth, const CoverageKey& key,
                                  const CoverageView& view) {
    const uint64_t bytes = passes::CoverageGrid::of(view.width, view.height).bytes();
    if (!tiles_ || tiles_->size != bytes) {
        tiles_ = backend_.createBuffer(bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Readback,
                                       "coverage buffer");
        valid_.reset();
    }
    graph.markOutput(passes::addCoverageBufferPass(graph, depth, graph.importBuffer("coverageBuffer", tiles_)));
    pending_ = Seen{key, view};
    // The buffer is overwritten by this frame: the last frame's is gone either way.
    valid_.reset();
}

void OcclusionHistory::frameDone() {
    valid_ = pending_;
    pending_.reset();
}

}  // namespace obscura::renderer
