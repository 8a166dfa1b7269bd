// Occlusion culling's coverage buffer (seed 004 "Occlusion culling"), the GPU half: the frame's
// opaque depth reduced to tiles of nearest and farthest depth (shaders/coverage_buffer.comp),
// written into a host-visible buffer that the next frame reads on the CPU after this frame's fence
// (the talk's one frame of latency) and reprojects into its own view (renderer/coverage_buffer.h).
#pragma once

#include "passes/frame_resources.h"

#include <cstdint>

namespace obscura::passes {

// A tile's side in pixels: 8x8 pixels make a 240x135 buffer at 1080p (the talk's consoles used
// 256x128).
constexpr uint32_t kCoverageTilePixels = 8;

struct CoverageGrid {
    uint32_t width = 0, height = 0;  // tiles

    static CoverageGrid of(uint32_t pixelsWide, uint32_t pixelsHigh) {
        return {(pixelsWide + kCoverageTilePixels - 1) / kCoverageTilePixels,
                (pixelsHigh + kCoverageTilePixels - 1) / kCoverageTilePixels};
    }
    // Bytes of the buffer: two floats (nearest, farthest device depth) per tile, row by row.
    uint64_t bytes() const { return uint64_t(width) * height * 2 * sizeof(float); }
};

// Reduces `depth` (the G-buffer's single-sample depth, or MSAA's farthest sample depth per pixel)
// into `tiles`, a buffer of CoverageGrid::bytes() for the depth's size; returns its written version.
gpu::BufferHandle addCoverageBufferPass(gpu::FrameGraph& graph, gpu::ImageHandle depth, gpu::BufferHandle tiles);

}  // namespace obscura::passes
