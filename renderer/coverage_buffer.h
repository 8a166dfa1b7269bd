// Occlusion culling's coverage buffer (seed 004 "Occlusion culling"), the CPU half: the last
// frame's tiles of nearest and farthest depth (passes/coverage_buffer.h), reprojected into this
// frame's view, against which each draw's and each instance's world bounds are tested before the
// frame is built.
//
// Conservative throughout: a box is hidden only where every pixel its screen rectangle touches
// holds an occluder nearer than its nearest point. A tile occludes only where it was fully covered
// (no background pixel), its reprojection stays in front of the eye, the reprojections of its
// nearest and its farthest depth agree within kMaxParallaxPixels (a tile spanning a depth
// discontinuity opens gaps as the eye moves; the talk's "use conservative occlusion to avoid false
// culling"), and then only over the rectangle inside both reprojected quads, at the pixels whose
// centres (where the rasteriser samples, the projection's jitter included) it holds: neighbouring
// tiles' rectangles meet without a gap. Everything else is a hole: no occluder. What the last frame
// drew must still be where it was (the renderer drops the history when anything drawn changed), and
// a history-less frame (the first, a camera cut) tests nothing.
// XXX: the depth is known at the last frame's sample points only: a gap narrower than a pixel
// that none of them saw through (two surfaces meeting inside one tile within the parallax
// allowance as the eye moves, or a crack the next jitter offset samples) is taken as covered.
#pragma once

#include "renderer/matrix.h"

#include <cstdint>
#include <vector>

namespace obscura::renderer {

// Seen from where, and into how many pixels: the view (world to view space, looking down -z) and
// the projection the frame rasterises with, temporal AA's jitter included.
struct CoverageView {
    Matrix4d view = kIdentity;
    Matrix4d projection = kIdentity;
    uint32_t width = 0, height = 0;
};

class CoverageBuffer {
public:
    // `tiles`: the last frame's nearest and farthest device depth per tile of `tilePixels`, row
    // by row, over an image of `current`'s size, rasterised through `last`.
    CoverageBuffer(const float* tiles, uint32_t tilePixels, const CoverageView& last, const CoverageView& current);

    // True when every point of the world-space box [min, max] lies behind an occluder of the
    // reprojected buffer, by the depth margin.
    bool hidden(const Vec3d& min, const Vec3d& max) const;

    // Pixels that hold an occluder: how much of the view is covered.
    uint64_t coveredPixels() const;
    // CPU time the reprojection took.
    double reprojectionMilliseconds() const { return reprojectionMilliseconds_; }

    // Pixels per side of the blocks whose farthest occluder lets a large box be tested a block at
    // a time.
    static constexpr uint32_t kBlockPixels = 8;
    // The largest disagreement, in pixels, between the reprojections of a tile's nearest and
    // farthest depth for the tile to occlude.
    static constexpr double kMaxParallaxPixels = 0.5;
    // Pixels a box's screen rectangle grows by: hybrid AA draws some instances without temporal
    // AA's jitter, up to half a pixel from where the jittered projection puts them.
    static constexpr double kScreenMarginPixels = 1.0;
    // A box must lie this fraction of the occluder's view depth behind it (the depth buffer's
    // precision, the tiles' float depths).
    static constexpr double kDepthMargin = 0.01;

private:
    void reprojectTile(const float nearestFarthest[2], const double pixelRect[4], const Matrix4d& lastClipToWorld);

    Matrix4d view_ = kIdentity;
    Matrix4d viewProjection_ = kIdentity;
    uint32_t width_ = 0, height_ = 0;
    uint32_t blocksWide_ = 0, blocksHigh_ = 0;
    // View depth of the occluder at each pixel; +infinity where none.
    std::vector<float> pixels_;
    // The farthest of each block's pixels.
    std::vector<float> blocks_;
    double reprojectionMilliseconds_ = 0.0;
};

}  // namespace obscura::renderer
