// Occlusion culling's coverage buffer on the CPU (renderer/coverage_buffer.h): the last frame's
// tiles of nearest and farthest depth, reprojected into this frame's view, hide only boxes that lie
// wholly behind fully covered, consistently reprojected tiles.
#include "renderer/coverage_buffer.h"

#include <gtest/gtest.h>

#include <vector>

namespace obscura::renderer {
namespace {

constexpr uint32_t kSize = 64, kTile = 8, kTiles = kSize / kTile;
constexpr double kNear = 0.1, kFar = 100.0;

// A square perspective projection with a 90-degree field of view and depth in [0, 1] (row vectors,
// looking down -z).
Matrix4d projection() {
    Matrix4d m{};
    m[0] = 1.0;
    m[5] = 1.0;
    m[10] = kFar / (kNear - kFar);
    m[11] = -1.0;
    m[14] = kNear * kFar / (kNear - kFar);
    return m;
}

// The device depth of a point `distance` in front of the eye.
float deviceDepth(double distance) {
    return float((kFar / (kNear - kFar) * -distance + kNear * kFar / (kNear - kFar)) / distance);
}

Matrix4d movedBy(double x, double y, double z) {
    Matrix4d m = kIdentity;  // the world moves the other way
    m[12] = -x, m[13] = -y, m[14] = -z;
    return m;
}

// Every tile covered by a wall facing the eye `distance` away.
std::vector<float> wallTiles(double distance) {
    std::vector<float> tiles;
    for (uint32_t i = 0; i < kTiles * kTiles; ++i) tiles.insert(tiles.end(), {deviceDepth(distance), deviceDepth(distance)});
    return tiles;
}

CoverageView viewFrom(const Matrix4d& view) { return {view, projection(), kSize, kSize}; }

TEST(CoverageBuffer, AWallHidesWhatIsBehindItAndNothingInFront) {
    std::vector<float> tiles = wallTiles(10.0);
    CoverageBuffer coverage(tiles.data(), kTile, viewFrom(kIdentity), viewFrom(kIdentity));
    EXPECT_EQ(coverage.coveredPixels(), uint64_t(kSize) * kSize);
    EXPECT_TRUE(coverage.hidden({-1, -1, -13}, {1, 1, -12}));
    EXPECT_FALSE(coverage.hidden({-1, -1, -6}, {1, 1, -5})) << "in front of the wall";
    EXPECT_FALSE(coverage.hidden({-1, -1, -11}, {1, 1, -9.5})) << "through the wall";
    EXPECT_FALSE(coverage.hidden({-1, -1, -10.05}, {1, 1, -10.02})) << "within the depth margin";
    EXPECT_FALSE(coverage.hidden({-1, -1, 1}, {1, 1, -12})) << "reaching behind the eye";
}

TEST(CoverageBuffer, ATileWithBackgroundIsAHole) {
    std::vector<float> tiles = wallTiles(10.0);
    tiles[2 * (3 * kTiles + 4) + 1] = 1.0f;  // tile (4, 3): one pixel saw the background
    CoverageBuffer coverage(tiles.data(), kTile, viewFrom(kIdentity), viewFrom(kIdentity));
    // Tile (4, 3) spans pixels x 32..40, y 24..32: x in [0, 2.5], y in [-2.5, 0] at depth 10.
    EXPECT_FALSE(coverage.hidden({0.5, -1.5, -10.5}, {0.7, -1.3, -10.4}));
    EXPECT_TRUE(coverage.hidden({-5.5, 4.0, -10.5}, {-5.0, 4.5, -10.4})) << "far from the hole";
}

TEST(CoverageBuffer, TheEyeMovingKeepsAFlatWallButNotADepthDiscontinuity) {
    std::vector<float> tiles = wallTiles(10.0);
    // Tile (2, 2) spans a silhouette: something at 3 in front of the wall.
    tiles[2 * (2 * kTiles + 2)] = deviceDepth(3.0);
    CoverageBuffer still(tiles.data(), kTile, viewFrom(kIdentity), viewFrom(kIdentity));
    CoverageBuffer moved(tiles.data(), kTile, viewFrom(kIdentity), viewFrom(movedBy(0.1, 0.0, 0.0)));
    // Behind the middle of the wall: hidden from both eyes.
    EXPECT_TRUE(still.hidden({-0.5, -0.5, -12}, {0.5, 0.5, -11}));
    EXPECT_TRUE(moved.hidden({-0.5, -0.5, -12}, {0.5, 0.5, -11}));
    // Behind tile (2, 2) (x and y in [-5, -2.5] at depth 10): the reprojections of its depths 3 and
    // 10 part by 0.75 pixels, more than kMaxParallaxPixels, once the eye moves.
    const Vec3d lo{-4.0, -3.7, -10.6}, hi{-3.8, -3.5, -10.5};
    EXPECT_TRUE(still.hidden(lo, hi));
    EXPECT_FALSE(moved.hidden(lo, hi));
}

TEST(CoverageBuffer, TheEyeMovingFarLeavesTheUncoveredEdgeOpen) {
    std::vector<float> tiles = wallTiles(10.0);
    // Two units to the right: the wall's reprojection leaves the right edge of the view uncovered.
    CoverageBuffer moved(tiles.data(), kTile, viewFrom(kIdentity), viewFrom(movedBy(2.0, 0.0, 0.0)));
    EXPECT_FALSE(moved.hidden({18.5, -0.5, -20.5}, {19.0, 0.5, -20.0})) << "seen past the wall's last edge";
    EXPECT_TRUE(moved.hidden({-0.5, -0.5, -20.5}, {0.5, 0.5, -20.0}));
}

}  // namespace
}  // namespace obscura::renderer
