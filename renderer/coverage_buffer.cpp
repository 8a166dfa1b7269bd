#include "renderer/coverage_buffer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

namespace obscura::renderer {
namespace {

constexpr float kNoOccluder = std::numeric_limits<float>::infinity();

struct ScreenPoint {
    double x, y;   // pixels
    double depth;  // view depth (distance along the view axis)
};

// [p, 1] x m, homogeneous.
std::array<double, 4> transformHomogeneous(const std::array<double, 4>& p, const Matrix4d& m) {
    std::array<double, 4> r{};
    for (size_t j = 0; j < 4; ++j) r[j] = p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + p[3] * m[12 + j];
    return r;
}

// Is `p` inside the convex quad `q` (corners in cyclic order, either winding)?
bool insideQuad(const std::array<ScreenPoint, 4>& q, double x, double y) {
    int positive = 0, negative = 0;
    for (size_t i = 0; i < 4; ++i) {
        const ScreenPoint& a = q[i];
        const ScreenPoint& b = q[(i + 1) % 4];
        double side = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
        positive += side > 0.0;
        negative += side < 0.0;
    }
    return positive == 0 || negative == 0;
}

}  // namespace

CoverageBuffer::CoverageBuffer(const float* tiles, uint32_t tilePixels, const CoverageView& last,
                               const CoverageView& current)
    : view_(current.view),
      viewProjection_(multiply(current.view, current.projection)),
      width_(current.width),
      height_(current.height),
      blocksWide_((current.width + kBlockPixels - 1) / kBlockPixels),
      blocksHigh_((current.height + kBlockPixels - 1) / kBlockPixels),
      pixels_(size_t(current.width) * current.height, kNoOccluder),
      blocks_(size_t(blocksWide_) * blocksHigh_, kNoOccluder) {
    const auto start = std::chrono::steady_clock::now();
    Matrix4d lastClipToWorld = kIdentity;
    if (!invert(multiply(last.view, last.projection), lastClipToWorld)) return;
    const uint32_t tilesWide = (width_ + tilePixels - 1) / tilePixels;
    const uint32_t tilesHigh = (height_ + tilePixels - 1) / tilePixels;
    for (uint32_t ty = 0; ty < tilesHigh; ++ty)
        for (uint32_t tx = 0; tx < tilesWide; ++tx) {
            const double rect[4] = {double(tx * tilePixels), double(ty * tilePixels),
                                    double(std::min((tx + 1) * tilePixels, width_)),
                                    double(std::min((ty + 1) * tilePixels, height_))};
            reprojectTile(tiles + 2 * (size_t(ty) * tilesWide + tx), rect, lastClipToWorld);
        }
    for (uint32_t y = 0; y < height_; ++y)
        for (uint32_t x = 0; x < width_; ++x) {
            float& block = blocks_[size_t(y / kBlockPixels) * blocksWide_ + x / kBlockPixels];
            const float pixel = pixels_[size_t(y) * width_ + x];
            block = (x % kBlockPixels == 0 && y % kBlockPixels == 0) ? pixel : std::max(block, pixel);
        }
    reprojectionMilliseconds_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void CoverageBuffer::reprojectTile(const float nearestFarthest[2], const double pixelRect[4],
                                   const Matrix4d& lastClipToWorld) {
    // A background pixel in the tile (depth cleared to 1): it hides nothing.
    if (!(nearestFarthest[1] < 1.0f) || !(nearestFarthest[0] <= nearestFarthest[1])) return;
    // The tile's corners at its nearest and its farthest depth, in this frame's pixels. Cyclic
    // order: (x0, y0), (x1, y0), (x1, y1), (x0, y1).
    std::array<std::array<ScreenPoint, 4>, 2> quads{};
    double farthestDepth = 0.0;
    for (size_t d = 0; d < 2; ++d)
        for (size_t c = 0; c < 4; ++c) {
            const double px = pixelRect[(c == 1 || c == 2) ? 2 : 0];
            const double py = pixelRect[c >= 2 ? 3 : 1];
            std::array<double, 4> world = transformHomogeneous(
                {2.0 * px / width_ - 1.0, 2.0 * py / height_ - 1.0, double(nearestFarthest[d]), 1.0}, lastClipToWorld);
            if (!(std::abs(world[3]) > 0.0)) return;
            const std::array<double, 4> point{world[0] / world[3], world[1] / world[3], world[2] / world[3], 1.0};
            const double depth = -transformHomogeneous(point, view_)[2];
            std::array<double, 4> clip = transformHomogeneous(point, viewProjection_);
            if (!(depth > 0.0) || !(clip[3] > 0.0)) return;  // behind the eye now
            quads[d][c] = {(clip[0] / clip[3] + 1.0) * 0.5 * width_, (clip[1] / clip[3] + 1.0) * 0.5 * height_, depth};
            // View depth is affine in world space: the chunk of the tile's frustum between its
            // depths lies in front of the farthest of these.
            farthestDepth = std::max(farthestDepth, depth);
        }
    for (size_t c = 0; c < 4; ++c)
        if (std::hypot(quads[0][c].x - quads[1][c].x, quads[0][c].y - quads[1][c].y) > kMaxParallaxPixels) return;
    // The rectangle inside both quads: each side the innermost of its two corners.
    double x0 = -std::numeric_limits<double>::infinity(), y0 = x0;
    double x1 = std::numeric_limits<double>::infinity(), y1 = x1;
    for (const auto& q : quads) {
        const double left = std::max(q[0].x, q[3].x), right = std::min(q[1].x, q[2].x);
        const double top = std::max(q[0].y, q[1].y), bottom = std::min(q[2].y, q[3].y);
        if (!(left < right) || !(top < bottom)) return;  // mirrored or thinner than nothing
        // A quad turned far from its tile's orientation: keep only a rectangle it really contains.
        for (double x : {left, right})
            for (double y : {top, bottom})
                if (!insideQuad(q, x, y)) return;
        x0 = std::max(x0, left);
        x1 = std::min(x1, right);
        y0 = std::max(y0, top);
        y1 = std::min(y1, bottom);
    }
    // The pixels whose centres the rectangle holds (edges included: neighbouring tiles' rectangles
    // share theirs).
    const auto first = [](double v, uint32_t limit) {
        return uint32_t(std::clamp(std::ceil(v - 0.5), 0.0, double(limit)));
    };
    const auto end = [](double v, uint32_t limit) {
        return uint32_t(std::clamp(std::floor(v - 0.5) + 1.0, 0.0, double(limit)));
    };
    const uint32_t px0 = first(x0, width_), px1 = end(x1, width_);
    const uint32_t py0 = first(y0, height_), py1 = end(y1, height_);
    for (uint32_t py = py0; py < py1; ++py)
        for (uint32_t px = px0; px < px1; ++px) {
            float& occluder = pixels_[size_t(py) * width_ + px];
            occluder = std::min(occluder, float(farthestDepth));
        }
}

bool CoverageBuffer::hidden(const Vec3d& min, const Vec3d& max) const {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, nearest = x0;
    double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
    for (size_t i = 0; i < 8; ++i) {
        const std::array<double, 4> corner{(i & 1) ? max[0] : min[0], (i & 2) ? max[1] : min[1],
                                           (i & 4) ? max[2] : min[2], 1.0};
        const double depth = -transformHomogeneous(corner, view_)[2];
        std::array<double, 4> clip = transformHomogeneous(corner, viewProjection_);
        // Reaching the eye's plane: its rectangle is unbounded.
        if (!(depth > 0.0) || !(clip[3] > 0.0)) return false;
        const double x = (clip[0] / clip[3] + 1.0) * 0.5 * width_, y = (clip[1] / clip[3] + 1.0) * 0.5 * height_;
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
        nearest = std::min(nearest, depth);
    }
    // The pixels the grown rectangle touches, [px0, px1) x [py0, py1).
    const auto pixelOf = [](double v, uint32_t limit) {
        return int64_t(std::clamp(std::floor(v), -1.0, double(limit) + 1.0));
    };
    const int64_t px0 = pixelOf(x0 - kScreenMarginPixels, width_), px1 = pixelOf(x1 + kScreenMarginPixels, width_) + 1;
    const int64_t py0 = pixelOf(y0 - kScreenMarginPixels, height_), py1 = pixelOf(y1 + kScreenMarginPixels, height_) + 1;
    // Off the screen on a side: frustum culling is not this test's to make.
    if (px1 <= 0 || py1 <= 0 || px0 >= int64_t(width_) || py0 >= int64_t(height_)) return false;
    const uint32_t x = uint32_t(std::max<int64_t>(px0, 0)), xEnd = uint32_t(std::min<int64_t>(px1, width_));
    const uint32_t y = uint32_t(std::max<int64_t>(py0, 0)), yEnd = uint32_t(std::min<int64_t>(py1, height_));
    const float limit = float(nearest / (1.0 + kDepthMargin));
    // A block at a time where the rectangle holds it whole, pixel by pixel along its edges.
    for (uint32_t by = y / kBlockPixels; by * kBlockPixels < yEnd; ++by)
        for (uint32_t bx = x / kBlockPixels; bx * kBlockPixels < xEnd; ++bx) {
            const uint32_t bx0 = std::max(bx * kBlockPixels, x), bx1 = std::min((bx + 1) * kBlockPixels, xEnd);
            const uint32_t by0 = std::max(by * kBlockPixels, y), by1 = std::min((by + 1) * kBlockPixels, yEnd);
            if (bx1 - bx0 == kBlockPixels && by1 - by0 == kBlockPixels) {
                if (!(blocks_[size_t(by) * blocksWide_ + bx] < limit)) return false;
                continue;
            }
            for (uint32_t py = by0; py < by1; ++py)
                for (uint32_t px = bx0; px < bx1; ++px)
                    if (!(pixels_[size_t(py) * width_ + px] < limit)) return false;
        }
    return true;
}

uint64_t CoverageBuffer::coveredPixels() const {
    return uint64_t(std::count_if(pixels_.begin(), pixels_.end(), [](float c) { return c < kNoOccluder; }));
}

}  // namespace obscura::renderer
