// The depth pyramid's size (passes/hi_z.h): every level from the half-size one down to a single
// texel, each side rounded up, as shaders/common/hi_z.glsl lays them out.
#include "passes/hi_z.h"

#include <gtest/gtest.h>

namespace obscura::passes {
namespace {

TEST(HiZPyramid, HoldsEveryLevelDownToOneTexel) {
    // 1920x1080: 960x540, 480x270, 240x135, 120x68, 60x34, 30x17, 15x9, 8x5, 4x3, 2x2, 1x1.
    EXPECT_EQ(hiZPyramidFloats(1920, 1080), 518400u + 129600u + 32400u + 8160u + 2040u + 510u + 135u + 40u + 12u +
                                                4u + 1u);
    // A side of one pixel keeps one texel across; 2x2 pixels make one texel at level 1.
    EXPECT_EQ(hiZPyramidFloats(1, 5), 3u + 2u + 1u);
    EXPECT_EQ(hiZPyramidFloats(2, 2), 1u);
    EXPECT_EQ(hiZPyramidFloats(1, 1), 1u);
}

}  // namespace
}  // namespace obscura::passes
