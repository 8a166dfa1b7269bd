// USD's velocity-based motion (delegate/prims/point_motion.h, Instancer's turnOrientations): the
// closed forms of UsdGeomPointBased / UsdGeomPointInstancer.
#include "delegate/prims/instancer.h"
#include "delegate/prims/point_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace obscura::delegate {
namespace {

TEST(PointMotion, PointsMoveByVelocityAndAcceleration) {
    std::vector<float> points{1, 2, 3, -1, 0, 0};
    auto motion = pointMotion(std::vector<float>{2, 0, 0, 0, 4, 0}, std::vector<float>{0, 0, 8, 0, 0, 0}, 2);
    ASSERT_TRUE(motion);
    std::vector<float> moved = movePoints(points, *motion, 0.5);
    // p + dt v + dt^2 a / 2 with dt = 0.5.
    std::vector<float> expected{2, 2, 4, -1, 2, 0};
    EXPECT_EQ(moved, expected);
    EXPECT_EQ(movePoints(points, *motion, 0.0), points);
}

TEST(PointMotion, VelocitiesOfAnotherCountAreNoMotion) {
    EXPECT_FALSE(pointMotion(std::vector<float>{1, 0, 0}, std::nullopt, 2));
    EXPECT_FALSE(pointMotion(std::nullopt, std::nullopt, 2));
    auto motion = pointMotion(std::vector<float>{1, 0, 0, 1, 0, 0}, std::vector<float>{1, 1, 1}, 2);
    ASSERT_TRUE(motion);
    EXPECT_TRUE(motion->accelerations.empty()) << "accelerations of another count are left out";
}

TEST(PointMotion, SamplesOfAnotherCountFallBackToTheFrame) {
    std::vector<float> frame{0, 0, 0};
    EXPECT_EQ(sampledOrFrame(std::vector<float>{1, 1, 1}, frame), (std::vector<float>{1, 1, 1}));
    EXPECT_EQ(sampledOrFrame(std::vector<float>{1, 1, 1, 2, 2, 2}, frame), frame);
    EXPECT_EQ(sampledOrFrame(std::nullopt, frame), frame);
    EXPECT_DOUBLE_EQ(secondsBetween(10.0, 13.0, 24.0), 0.125);
}

// An angular velocity turns after the orientation: a bar along X turned 90 degrees about Z lies
// along Y; 90 degrees a second about X for one second then stands it along Z.
TEST(PointMotion, AngularVelocityTurnsAfterTheOrientation) {
    const float h = float(std::sqrt(0.5));
    std::vector<float> turned = turnOrientations({h, 0, 0, h}, {90, 0, 0}, 1.0);
    float zero[3] = {0, 0, 0};
    Matrix4d m = instanceTransform(zero, turned.data(), nullptr);
    // Row 0 is where the local X axis goes (row-vector convention).
    EXPECT_NEAR(m[0], 0.0, 1e-6);
    EXPECT_NEAR(m[1], 0.0, 1e-6);
    EXPECT_NEAR(m[2], 1.0, 1e-6);
    // No angular speed, or no time: the orientation as it was.
    EXPECT_EQ(turnOrientations({h, 0, 0, h}, {0, 0, 0}, 1.0), (std::vector<float>{h, 0, 0, h}));
    std::vector<float> still = turnOrientations({h, 0, 0, h}, {90, 0, 0}, 0.0);
    for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(still[i], (std::vector<float>{h, 0, 0, h})[i], 1e-7);
}

}  // namespace
}  // namespace obscura::delegate
