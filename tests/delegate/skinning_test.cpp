// UsdSkel through the harness's scene host and the plugin: an arm whose elbow bends is drawn where
// linear blend skinning puts it, blurred along its swing within the shutter, and drawn unskinned
// (with the problem reported where it is authored) when its joint influences are bad. A camera at
// z = 5 whose view fills [-1.04775, 1.04775]^2 at z = 0 looks at the arm.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace obscura::test {
namespace {

constexpr double kHalfView = 1.04775;

// The pixel (column, row) that (x, y) at z = 0 is drawn at.
std::pair<int, int> pixelOf(double x, double y) {
    return {int((x / kHalfView + 1.0) * kWidth / 2), int((1.0 - y / kHalfView) * kHeight / 2)};
}

// The arm: two quads along X, 0.2 high: the upper arm from -0.9 to 0 follows joint "root" (at
// x = -1), the forearm from 0 to 0.9 joint "root/elbow" (at the origin). The elbow turns about +Z
// by 90 degrees per time code from time 0. The shutter spans [-halfShutter, halfShutter] around
// the frame.
std::string armStage(const std::string& jointIndices, double halfShutter = 0.0) {
    return "#usda 1.0\n" +
           usdaCamera("    double shutter:open = " + std::to_string(-halfShutter) + "\n    double shutter:close = " +
                      std::to_string(halfShutter) + "\n") +
           R"(def SkelRoot "Rig"
{
    def Skeleton "Skel"
    {
        uniform token[] joints = ["root", "root/elbow"]
        uniform matrix4d[] bindTransforms = [((1,0,0,0),(0,1,0,0),(0,0,1,0),(-1,0,0,1)), ((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,0,1))]
        uniform matrix4d[] restTransforms = [((1,0,0,0),(0,1,0,0),(0,0,1,0),(-1,0,0,1)), ((1,0,0,0),(0,1,0,0),(0,0,1,0),(1,0,0,1))]
        rel skel:animationSource = </Rig/Skel/Anim>

        def SkelAnimation "Anim"
        {
            uniform token[] joints = ["root", "root/elbow"]
            float3[] translations = [(-1, 0, 0), (1, 0, 0)]
            quatf[] rotations.timeSamples = {
                0: [(1, 0, 0, 0), (1, 0, 0, 0)],
                1: [(1, 0, 0, 0), (0.70710678, 0, 0, 0.70710678)],
                2: [(1, 0, 0, 0), (0, 0, 0, 1)],
            }
        }
    }
    rel skel:skeleton = </Rig/Skel>

    def Mesh "Arm"
    {
        point3f[] points = [(-0.9, -0.1, 0), (0, -0.1, 0), (0, 0.1, 0), (-0.9, 0.1, 0),
                            (0, -0.1, 0), (0.9, -0.1, 0), (0.9, 0.1, 0), (0, 0.1, 0)]
        int[] faceVertexCounts = [4, 4]
        int[] faceVertexIndices = [0, 1, 2, 3, 4, 5, 6, 7]
        uniform token subdivisionScheme = "none"
        int[] primvars:skel:jointIndices = )" +
           jointIndices + R"( (
            interpolation = "vertex"
        )
        float[] primvars:skel:jointWeights = [1, 1, 1, 1, 1, 1, 1, 1] (
            interpolation = "vertex"
        )
    }
}
)";
}

const char* kGoodIndices = "[0, 0, 0, 0, 1, 1, 1, 1]";

bool drawnAt(const std::vector<float>& ids, double x, double y) {
    auto [px, py] = pixelOf(x, y);
    return ids[size_t(py) * kWidth + size_t(px)] >= 0.0f;
}

TEST(Skinning, TheArmIsDrawnWhereItsJointsPutIt) {
    HostedStage scene(usda::Stage::openFromString(armStage(kGoodIndices), "arm.usda"));
    auto straight = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(straight.size(), size_t(kWidth) * kHeight);
    EXPECT_TRUE(drawnAt(straight, 0.5, 0.0));
    EXPECT_FALSE(drawnAt(straight, 0.0, 0.5));
    // At time 1 the forearm points up: it left (0.5, 0) for (0, 0.5); the upper arm stays.
    ASSERT_EQ(scene.host->markTimeVarying(scene.api(), scene.delegate), OBSCURA_OK);
    auto bent = scene.renderAov("primId", 1, 1.0);
    EXPECT_FALSE(drawnAt(bent, 0.5, 0.0));
    EXPECT_TRUE(drawnAt(bent, 0.0, 0.5));
    EXPECT_TRUE(drawnAt(bent, -0.5, 0.0));
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
}

TEST(Skinning, TheSwingWithinTheShutterIsItsMotion) {
    // A shutter of 0.1 time codes: the forearm turns 9 degrees, and covers the pixel looked at
    // whatever instant of the shutter a frame draws.
    HostedStage scene(usda::Stage::openFromString(armStage(kGoodIndices, 0.05), "arm.usda"));
    auto motion = scene.renderAov("motion", 3, 1.0);
    ASSERT_EQ(motion.size(), size_t(kWidth) * kHeight * 3);
    // A point 0.5 up the upright forearm moves from 4.5 degrees before upright to 4.5 after:
    // the chord from open to close is 2 * 0.5 * sin(4.5 deg) long, towards -X.
    auto [px, py] = pixelOf(0.0, 0.5);
    const size_t at = (size_t(py) * kWidth + size_t(px)) * 3;
    const double chord = 2.0 * 0.5 * std::sin(4.5 * M_PI / 180.0) * kWidth / (2.0 * kHalfView);
    EXPECT_NEAR(motion[at], -chord, 0.1 * chord);
    EXPECT_NEAR(motion[at + 1], 0.0, 0.1 * chord);
    // The upper arm does not move.
    auto [qx, qy] = pixelOf(-0.5, 0.0);
    const size_t still = (size_t(qy) * kWidth + size_t(qx)) * 3;
    EXPECT_NEAR(motion[still], 0.0, 1e-3);
    EXPECT_NEAR(motion[still + 1], 0.0, 1e-3);
}

TEST(Skinning, BadJointIndicesAreReportedAndTheArmIsDrawnUnskinned) {
    HostedStage scene(usda::Stage::openFromString(armStage("[0, 0, 0, 0, 7, 1, 1, 1]"), "bad_arm.usda"));
    auto ids = scene.renderAov("primId", 1, 1.0);
    ASSERT_EQ(ids.size(), size_t(kWidth) * kHeight);
    // Unskinned: the strip lies straight along X as its points are authored.
    EXPECT_TRUE(drawnAt(ids, 0.5, 0.0));
    EXPECT_FALSE(drawnAt(ids, 0.0, 0.5));
    ASSERT_EQ(scene.host->messages().size(), 1u);
    const harness::HostMessage& message = scene.host->messages().front();
    EXPECT_TRUE(message.error);
    EXPECT_NE(message.text.find("/Rig/Arm: primvars:skel:jointIndices[4] = 7 is outside the 2 joints; drawn unskinned"),
              std::string::npos)
        << message.text;
    const std::string text = armStage("[0, 0, 0, 0, 7, 1, 1, 1]");
    const int line = int(std::count(text.begin(), text.begin() + long(text.find("int[] primvars:skel:jointIndices")), '\n')) + 1;
    EXPECT_EQ(message.where.file, "bad_arm.usda");
    EXPECT_EQ(message.where.line, line);
    EXPECT_GT(message.where.column, 0);
}

// A skeleton alone, drawn as a guide when includedPurposes names guide (as Storm draws bones): the
// bones join root (x = -1) to elbow (the origin) and elbow to hand (x = 1); the elbow turns about
// +Z by 90 degrees at time 1. Each bone is a square pyramid from its parent joint, its base a fifth
// of its length wide, its sides facing the camera, so a point 0.2 along a bone of length 1 lies
// within 0.08 of its axis.
const std::string kSkeletonOnly = "#usda 1.0\n" + usdaCamera() + R"(def SkelRoot "Rig"
{
    def Skeleton "Skel"
    {
        uniform token[] joints = ["root", "root/elbow", "root/elbow/hand"]
        uniform matrix4d[] bindTransforms = [((1,0,0,0),(0,1,0,0),(0,0,1,0),(-1,0,0,1)), ((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,0,1)), ((1,0,0,0),(0,1,0,0),(0,0,1,0),(1,0,0,1))]
        rel skel:animationSource = </Rig/Skel/Anim>

        def SkelAnimation "Anim"
        {
            uniform token[] joints = ["root/elbow"]
            float3[] translations = [(1, 0, 0)]
            quatf[] rotations.timeSamples = {
                0: [(1, 0, 0, 0)],
                1: [(0.70710678, 0, 0, 0.70710678)],
            }
        }
    }
}
)";

TEST(Skinning, SkeletonBonesAreDrawnOnlyAsGuides) {
    HostedStage scene(usda::Stage::openFromString(kSkeletonOnly, "skeleton.usda"));
    auto plain = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(plain.size(), size_t(kWidth) * kHeight);
    EXPECT_TRUE(std::all_of(plain.begin(), plain.end(), [](float id) { return id < 0.0f; }))
        << "bones drawn without the guide purpose";

    scene.setToken("includedPurposes", "default,render,guide");
    auto guides = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(guides.size(), size_t(kWidth) * kHeight);
    EXPECT_TRUE(drawnAt(guides, -0.8, 0.0)) << "root to elbow";
    EXPECT_TRUE(drawnAt(guides, -0.8, 0.05));
    EXPECT_FALSE(drawnAt(guides, -0.8, 0.15)) << "wider than the bone";
    EXPECT_TRUE(drawnAt(guides, 0.2, 0.0)) << "elbow to hand";
    EXPECT_FALSE(drawnAt(guides, 0.0, 0.5));
    EXPECT_FALSE(drawnAt(guides, -1.0, 0.5));
    // The elbow turns: the hand's bone now points up.
    ASSERT_EQ(scene.host->markTimeVarying(scene.api(), scene.delegate), OBSCURA_OK);
    auto bent = scene.renderAov("primId", 1, 1.0);
    EXPECT_TRUE(drawnAt(bent, 0.0, 0.2));
    EXPECT_FALSE(drawnAt(bent, 0.5, 0.0));
    EXPECT_TRUE(drawnAt(bent, -0.8, 0.0));
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
}

TEST(Skinning, ASkeletonWhoseDataDoesNotFitItsJointsIsReportedAndDrawsNoBones) {
    std::string text = kSkeletonOnly;
    const std::string bind = "uniform matrix4d[] bindTransforms = [";
    const size_t at = text.find(bind) + bind.size();
    text.erase(at, text.find("), (", at) + 3 - at);  // the root's bind transform left out: 2 for 3 joints
    HostedStage scene(usda::Stage::openFromString(text, "bad_skeleton.usda"));
    scene.setToken("includedPurposes", "default,render,guide");
    auto ids = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(ids.size(), size_t(kWidth) * kHeight);
    EXPECT_TRUE(std::all_of(ids.begin(), ids.end(), [](float id) { return id < 0.0f; }));
    ASSERT_EQ(scene.host->messages().size(), 1u);
    const harness::HostMessage& message = scene.host->messages().front();
    EXPECT_NE(message.text.find("/Rig/Skel: its Skeleton </Rig/Skel> has 2 bindTransforms for 3 joints; its bones are "
                                "not drawn"),
              std::string::npos)
        << message.text;
    EXPECT_EQ(message.where.file, "bad_skeleton.usda");
    EXPECT_EQ(message.where.line, 16);  // the bindTransforms
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

}  // namespace
}  // namespace obscura::test
