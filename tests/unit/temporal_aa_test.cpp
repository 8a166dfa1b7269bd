// Temporal AA bookkeeping without a GPU: the jitter sequence (offsets inside the pixel, well
// spread, the first at the centre), the history's resets and the converged flag, and the
// reprojection matrix (an unchanged camera maps each pixel onto itself whatever the jitter; a
// moved camera maps a point to where last frame saw it).
#include "renderer/temporal_accumulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace obscura::renderer {
namespace {

using passes::TemporalAaMode;

TEST(TemporalAaJitter, OffsetsStayInsideThePixelAndSpreadOverIt) {
    for (uint32_t count : {8u, 16u, 32u}) {
        std::set<int> columns, rows;
        std::array<std::array<int, 4>, 4> cells{};
        double meanX = 0, meanY = 0, closest = 1e9;
        std::vector<std::array<double, 2>> points;
        for (uint32_t i = 0; i < count; ++i) {
            auto [x, y] = passes::temporalAaJitter(TemporalAaMode::Smaa1tx, i, count);
            EXPECT_GE(x, -0.5);
            EXPECT_LT(x, 0.5);
            EXPECT_GE(y, -0.5);
            EXPECT_LT(y, 0.5);
            columns.insert(int(std::floor((x + 0.5) * count)));
            rows.insert(int(std::floor((y + 0.5) * count)));
            cells[size_t((x + 0.5) * 4)][size_t((y + 0.5) * 4)]++;
            meanX += x / count;
            meanY += y / count;
            for (const auto& p : points) closest = std::min(closest, std::hypot(p[0] - x, p[1] - y));
            points.push_back({x, y});
        }
        // A (0, 2)-sequence stratifies x and y exactly: one offset in each 1/count-wide column and
        // in each row.
        EXPECT_EQ(columns.size(), count);
        EXPECT_EQ(rows.size(), count);
        // Over a 4x4 grid of cells, none is crowded and few are left empty ...
        int occupied = 0;
        for (const auto& row : cells)
            for (int n : row) {
                EXPECT_LE(n, int(count / 16) + 1);
                occupied += n > 0;
            }
        EXPECT_GE(occupied, int(std::min(count, 16u)) * 3 / 4);
        // ... the centroid stays near the pixel centre (the rows' to frame 0's half a row from its
        // row's centre, over count offsets), and the share of the offsets above a horizontal edge
        // anywhere across the pixel is its coverage within one row (Halton's base 3 rows: 0.125 for
        // 8 and 16 offsets, 0.0625 for 32).
        EXPECT_LT(std::fabs(meanX), 1.0 / count + 1e-12);
        EXPECT_LE(std::fabs(meanY), 0.5 / (count * count) + 1e-12);
        double worst = 0.0;
        for (int step = 0; step <= 1000; ++step) {
            const double edge = step / 1000.0 - 0.5;
            double above = 0.0;
            for (const auto& p : points) above += p[1] < edge ? 1.0 / count : 0.0;
            worst = std::max(worst, std::fabs(above - (edge + 0.5)));
        }
        EXPECT_LE(worst, 1.0 / count + 1e-9);
        std::printf("%u offsets: centroid (%.4f, %.4f), closest pair %.3f pixels, horizontal edge's coverage within %.4f\n",
                    count, meanX, meanY, closest, worst);
    }
    auto first = passes::temporalAaJitter(TemporalAaMode::Smaa1tx, 0, 16);
    EXPECT_EQ(first[0], 0.0);
    EXPECT_EQ(first[1], 0.0);
    // The sequence repeats with its length.
    EXPECT_EQ(passes::temporalAaJitter(TemporalAaMode::Smaa1tx, 21, 16),
              passes::temporalAaJitter(TemporalAaMode::Smaa1tx, 5, 16));
    // 2TX: the two diagonal quarter-pixel offsets, alternating.
    auto a = passes::temporalAaJitter(TemporalAaMode::Smaa2tx, 0, 2), b = passes::temporalAaJitter(TemporalAaMode::Smaa2tx, 1, 2);
    EXPECT_EQ(a[0] + b[0], 0.0);
    EXPECT_EQ(a[1] + b[1], 0.0);
    EXPECT_EQ(std::fabs(a[0]), 0.25);
}

// A perspective camera at `eye` looking down -Z (row-vector convention), as delegate/prims/camera.cpp
// builds it for a 90-degree square view with near 0.1 and far 100.
Matrix4d viewFrom(Vec3d eye) {
    Matrix4d view = kIdentity;
    view[12] = -eye[0];
    view[13] = -eye[1];
    view[14] = -eye[2];
    return view;
}
const Matrix4d kProjection = [] {
    double n = 0.1, f = 100.0;
    Matrix4d c{};  // column-vector form, transposed below
    c[0] = 1.0;
    c[5] = -1.0;
    c[10] = f / (n - f);
    c[11] = n * f / (n - f);
    c[14] = -1.0;
    return transpose(c);
}();

std::array<double, 4> transformRow(const passes::Mat4& m, std::array<double, 4> v) {
    std::array<double, 4> out{};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) out[j] += v[i] * m[i * 4 + j];
    return out;
}
std::array<double, 4> transformRow(const Matrix4d& m, std::array<double, 4> v) {
    std::array<double, 4> out{};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) out[j] += v[i] * m[i * 4 + j];
    return out;
}

TEST(TemporalAccumulation, ResetsAndConvergence) {
    TemporalAccumulation taa;
    uint64_t scene = 0;  // the delegate's scene version
    TemporalAaKey key{"/Camera", 64, 64, 7};
    Matrix4d view = viewFrom({0, 0, 5});
    TemporalAaStep first = taa.next(key, ++scene, TemporalAaMode::Smaa1tx, 4, view, kProjection);
    EXPECT_FALSE(first.pass.historyValid);
    EXPECT_EQ(first.jitter, (std::array<double, 2>{0.0, 0.0}));
    EXPECT_FALSE(first.converged);
    // Three more frames of the still: the mean grows, the jitter walks the sequence.
    for (uint32_t held = 1; held < 4; ++held) {
        TemporalAaStep step = taa.next(key, scene, TemporalAaMode::Smaa1tx, 4, view, kProjection);
        EXPECT_TRUE(step.pass.historyValid);
        EXPECT_EQ(step.pass.heldFrames, held);
        EXPECT_TRUE(step.pass.unchanged);
        EXPECT_EQ(step.jitter, passes::temporalAaJitter(TemporalAaMode::Smaa1tx, held, 4));
        EXPECT_FALSE(step.converged);
    }
    // The mean is complete: one frame through the pixel centres, and it says so.
    for (int again = 0; again < 2; ++again) {
        TemporalAaStep settled = taa.next(key, scene, TemporalAaMode::Smaa1tx, 4, view, kProjection);
        EXPECT_EQ(settled.pass.heldFrames, 4u);
        EXPECT_EQ(settled.jitter, (std::array<double, 2>{0.0, 0.0}));
        EXPECT_TRUE(settled.converged);
    }
    // The scene changed: the history is kept (reprojected, clamped) but the mean restarts.
    TemporalAaStep changed = taa.next(key, ++scene, TemporalAaMode::Smaa1tx, 4, view, kProjection);
    EXPECT_TRUE(changed.pass.historyValid);
    EXPECT_EQ(changed.pass.heldFrames, 0u);
    EXPECT_FALSE(changed.pass.unchanged);
    EXPECT_FALSE(changed.converged);
    // The still after it starts its mean afresh: four frames of its own, then the settled one.
    for (uint32_t held = 0; held < 4; ++held) {
        TemporalAaStep step = taa.next(key, scene, TemporalAaMode::Smaa1tx, 4, view, kProjection);
        EXPECT_TRUE(step.pass.unchanged);
        EXPECT_EQ(step.pass.heldFrames, held);
        EXPECT_FALSE(step.converged);
    }
    EXPECT_TRUE(taa.next(key, scene, TemporalAaMode::Smaa1tx, 4, view, kProjection).converged);
    // A new size, another camera, a changed setting: the history is gone.
    for (TemporalAaKey other : {TemporalAaKey{"/Camera", 32, 64, 7}, TemporalAaKey{"/Other", 64, 64, 7},
                                TemporalAaKey{"/Camera", 64, 64, 8}}) {
        TemporalAaStep reset = taa.next(other, scene, TemporalAaMode::Smaa1tx, 4, view, kProjection);
        EXPECT_FALSE(reset.pass.historyValid);
        EXPECT_EQ(reset.jitter, (std::array<double, 2>{0.0, 0.0}));
        taa.next(key, scene, TemporalAaMode::Smaa1tx, 4, view, kProjection);
    }
    // Off and on again: afresh.
    taa.reset();
    EXPECT_FALSE(taa.next(key, scene, TemporalAaMode::Smaa1tx, 4, view, kProjection).pass.historyValid);
    // One frame to converge: the first, unjittered, frame is final.
    TemporalAccumulation single;
    EXPECT_TRUE(single.next(key, 1, TemporalAaMode::Smaa1tx, 1, view, kProjection).converged);
    // 2TX: two frames.
    TemporalAccumulation twoFrame;
    EXPECT_FALSE(twoFrame.next(key, 1, TemporalAaMode::Smaa2tx, 16, view, kProjection).converged);
    EXPECT_TRUE(twoFrame.next(key, 1, TemporalAaMode::Smaa2tx, 16, view, kProjection).converged);
}

// Motion blur in a still: the first frame after a reset is the real-time one (whole shutter, not
// in the mean); then taa:frames samples, each its own stratum of the shutter (every 1/N once) and
// the jitter offsets in the order of a still without motion blur; then the settled frame, through
// the pixel centres, keeping the mean that already holds the whole shutter.
TEST(TemporalAccumulation, StillSamplesTheShutterInStrata) {
    TemporalAccumulation taa;
    uint64_t scene = 1;
    TemporalAaKey key{"/Camera", 64, 64, 0};
    Matrix4d view = viewFrom({0, 0, 5});
    constexpr uint32_t kFrames = 8;
    TemporalAaStep first = taa.next(key, scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = true});
    EXPECT_FALSE(first.shutterStratum.has_value());
    EXPECT_FALSE(first.shutterAccumulated);
    std::vector<int> covered(kFrames, 0);
    for (uint32_t held = 0; held < kFrames; ++held) {
        TemporalAaStep step = taa.next(key, scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = true});
        EXPECT_EQ(step.pass.heldFrames, held);
        EXPECT_TRUE(step.pass.unchanged);
        EXPECT_EQ(step.jitter, passes::temporalAaJitter(TemporalAaMode::Smaa1tx, held, kFrames));
        ASSERT_TRUE(step.shutterStratum.has_value());
        auto [start, end] = *step.shutterStratum;
        EXPECT_NEAR(end - start, 1.0 / kFrames, 1e-12);
        ++covered[size_t(std::lround(start * kFrames))];
        EXPECT_FALSE(step.converged);
    }
    EXPECT_EQ(covered, std::vector<int>(kFrames, 1));
    TemporalAaStep settled = taa.next(key, scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = true});
    EXPECT_FALSE(settled.shutterStratum.has_value());
    EXPECT_TRUE(settled.shutterAccumulated);
    EXPECT_EQ(settled.jitter, (std::array<double, 2>{0.0, 0.0}));
    EXPECT_TRUE(settled.converged);
    // A change: the real-time frame again, then the strata afresh.
    TemporalAaStep changed = taa.next(key, ++scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = true});
    EXPECT_FALSE(changed.shutterStratum.has_value() || changed.shutterAccumulated || changed.converged);
    TemporalAaStep again = taa.next(key, scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = true});
    EXPECT_EQ(again.pass.heldFrames, 0u);
    ASSERT_TRUE(again.shutterStratum.has_value());
    EXPECT_EQ((*again.shutterStratum)[0], 0.0);
    // 2TX keeps no mean: every frame is the real-time one.
    TemporalAccumulation twoFrame;
    for (int frame = 0; frame < 3; ++frame) {
        TemporalAaStep step = twoFrame.next(key, 1, TemporalAaMode::Smaa2tx, kFrames, view, kProjection, {.shutter = true});
        EXPECT_FALSE(step.shutterStratum.has_value() || step.shutterAccumulated);
    }
}

// Depth of field in a still: the first frame after a reset looks through the lens's centre (the
// real-time one, not in the mean); then taa:frames samples, each its own stratum of the aperture
// (every one once), with the jitter offsets in the order of a still without depth of field; then
// the settled frame, through the lens's centre and the pixel centres, keeping the mean.
TEST(TemporalAccumulation, StillSamplesTheLensInStrata) {
    TemporalAccumulation taa;
    uint64_t scene = 1;
    TemporalAaKey key{"/Camera", 64, 64, 0};
    Matrix4d view = viewFrom({0, 0, 5});
    constexpr uint32_t kFrames = 8;
    for (bool shutter : {false, true}) {
        taa.reset();
        TemporalAaStep first = taa.next(key, scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = shutter, .lens = true});
        EXPECT_FALSE(first.lensStratum.has_value() || first.lensAccumulated || first.converged);
        std::vector<int> covered(kFrames, 0);
        for (uint32_t held = 0; held < kFrames; ++held) {
            TemporalAaStep step = taa.next(key, scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = shutter, .lens = true});
            EXPECT_EQ(step.pass.heldFrames, held);
            EXPECT_EQ(step.jitter, passes::temporalAaJitter(TemporalAaMode::Smaa1tx, held, kFrames));
            ASSERT_TRUE(step.lensStratum.has_value());
            ASSERT_LT(*step.lensStratum, kFrames);
            ++covered[*step.lensStratum];
            EXPECT_EQ(step.shutterStratum.has_value(), shutter);
            EXPECT_FALSE(step.converged);
        }
        EXPECT_EQ(covered, std::vector<int>(kFrames, 1));
        TemporalAaStep settled = taa.next(key, scene, TemporalAaMode::Smaa1tx, kFrames, view, kProjection, {.shutter = shutter, .lens = true});
        EXPECT_FALSE(settled.lensStratum.has_value());
        EXPECT_TRUE(settled.lensAccumulated);
        EXPECT_EQ(settled.shutterAccumulated, shutter);
        EXPECT_TRUE(settled.converged);
    }
    // 2TX keeps no mean: every frame looks through the lens's centre.
    TemporalAccumulation twoFrame;
    for (int frame = 0; frame < 3; ++frame) {
        TemporalAaStep step = twoFrame.next(key, 1, TemporalAaMode::Smaa2tx, kFrames, view, kProjection, {.lens = true});
        EXPECT_FALSE(step.lensStratum.has_value() || step.lensAccumulated);
    }
}

TEST(TemporalAccumulation, ReprojectionMapsPixelsToLastFramesImage) {
    TemporalAccumulation taa;
    uint64_t scene = 0;
    TemporalAaKey key{"/Camera", 64, 64, 0};
    Matrix4d view = viewFrom({0, 0, 5});
    taa.next(key, ++scene, TemporalAaMode::Smaa1tx, 16, view, kProjection);
    // Same camera, another jitter: every clip position maps onto itself.
    TemporalAaStep still = taa.next(key, scene, TemporalAaMode::Smaa1tx, 16, view, kProjection);
    ASSERT_NE(still.jitter, (std::array<double, 2>{0.0, 0.0}));
    for (std::array<double, 4> clip : {std::array<double, 4>{0.3, -0.7, 0.9, 1.0}, {-1.0, 1.0, 0.2, 1.0}}) {
        auto mapped = transformRow(still.pass.currentClipToPreviousClip, clip);
        EXPECT_NEAR(mapped[0] / mapped[3], clip[0], 1e-5);
        EXPECT_NEAR(mapped[1] / mapped[3], clip[1], 1e-5);
    }
    // The camera moves right: a world point seen now maps to where last frame's (jittered) image
    // showed it, and to its depth along last frame's view axis.
    Matrix4d moved = viewFrom({0.2, 0.1, 4.5});
    TemporalAaStep step = taa.next(key, ++scene, TemporalAaMode::Smaa1tx, 16, moved, kProjection);
    std::array<double, 4> world{0.4, -0.3, -2.0, 1.0};
    auto current = transformRow(multiply(moved, multiply(kProjection, step.clipJitter)), world);
    auto previous = transformRow(multiply(view, multiply(kProjection, step.clipJitter)), world);
    auto mapped = transformRow(step.pass.currentClipToPreviousClip, current);
    EXPECT_NEAR(mapped[0] / mapped[3], previous[0] / previous[3], 1e-5);
    EXPECT_NEAR(mapped[1] / mapped[3], previous[1] / previous[3], 1e-5);
    auto previousView = transformRow(step.pass.currentClipToPreviousView, current);
    EXPECT_NEAR(-previousView[2] / previousView[3], 7.0, 1e-4);  // the point lay 7 units in front of the old eye
}

}  // namespace
}  // namespace obscura::renderer
