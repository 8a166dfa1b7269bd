#include "passes/coverage_buffer.h"

#include "generated/shader_layouts.h"
#include "passes/shader_pass.h"

#include <array>

namespace obscura::passes {
namespace {

// Mirrors the push constants of shaders/coverage_buffer.comp.
struct CoveragePush {
    std::array<uint32_t, 2> tiles;
    uint32_t tilePixels;
};
OBSCURA_SHADER_OFFSET(CoveragePush, coverage_buffer_comp::Push, tiles);
OBSCURA_SHADER_OFFSET(CoveragePush, coverage_buffer_comp::Push, tilePixels);

}  // namespace

gpu::BufferHandle addCoverageBufferPass(gpu::FrameGraph& graph, gpu::ImageHandle depth, gpu::BufferHandle tiles) {
    const gpu::ImageDesc desc = graph.imageDesc(depth);
    const CoverageGrid grid = CoverageGrid::of(desc.width, desc.height);
    CoveragePush push{{grid.width, grid.height}, kCoverageTilePixels};
    ComputePass pass{"coverage_buffer", {sampled(depth), bufferWrite(tiles)}, bytesOf(push)};
    pass.texels = std::array<uint32_t, 2>{grid.width, grid.height};  // one invocation per tile
    return addComputePass(graph, std::move(pass)).buffers[0];
}

}  // namespace obscura::passes
