// A Skeleton's guide mesh (usda/skeleton_bones.h): one square pyramid per bone, its apex at the
// joint and its base around the parent joint, a tenth of the bone's length from the axis on each
// side, perpendicular to the bone; the topology stays as the pose changes.
#include "harness/usda/skeleton_bones.h"
#include "usda_test_util.h"

#include <cmath>

namespace obscura::usda::test {
namespace {

// Joints "a" at (0, 0, 2), "a/b" 3 along +Y from it; at time 1 "a/b" is 3 along +X instead.
const char* kTwoJoints = R"(#usda 1.0
def Skeleton "Skel"
{
    uniform token[] joints = ["a", "a/b"]
    uniform matrix4d[] bindTransforms = [((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,2,1)), ((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,3,2,1))]
    rel skel:animationSource = </Skel/Anim>
    def SkelAnimation "Anim"
    {
        uniform token[] joints = ["a/b"]
        float3[] translations.timeSamples = { 0: [(0, 3, 0)], 1: [(3, 0, 0)] }
        quatf[] rotations = [(1, 0, 0, 0)]
    }
}
)";

TEST(SkeletonBones, EachBoneIsAPyramidFromItsParentJoint) {
    auto stage = open(kTwoJoints, "bones.usda");
    ASSERT_TRUE(stage);
    auto resolved = resolveSkeleton(*stage, *stage->find("/Skel"));
    ASSERT_TRUE(std::holds_alternative<Skinning>(resolved));
    const Skinning& skeleton = std::get<Skinning>(resolved);
    EXPECT_EQ(boneCount(skeleton), 1u);
    for (double time : {0.0, 1.0}) {
        std::string problem;
        const BoneMesh bones = boneMesh(skeleton, time, &problem);
        EXPECT_TRUE(problem.empty()) << problem;
        ASSERT_EQ(bones.points.numbers.size(), 15u);
        EXPECT_EQ(bones.faceVertexCounts.numbers, (std::vector<double>{3, 3, 3, 3, 4}));
        EXPECT_EQ(bones.faceVertexIndices.numbers.size(), 16u);
        const double parent[3] = {0, 0, 2};
        const double joint[3] = {time == 0.0 ? 0.0 : 3.0, time == 0.0 ? 3.0 : 0.0, 2};
        for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(bones.points.numbers[12 + c], joint[c], 1e-9) << "apex";
        for (size_t corner = 0; corner < 4; ++corner) {
            double offset[3], along = 0, across = 0;
            for (size_t c = 0; c < 3; ++c) {
                offset[c] = bones.points.numbers[3 * corner + c] - parent[c];
                along += offset[c] * (joint[c] - parent[c]) / 3.0;
            }
            for (size_t c = 0; c < 3; ++c) across += offset[c] * offset[c];
            EXPECT_NEAR(along, 0.0, 1e-9) << "the base is perpendicular to the bone";
            // A square of half-width 0.1 * 3 has its corners sqrt(2) times that from its centre.
            EXPECT_NEAR(std::sqrt(across), std::sqrt(2.0) * kBoneHalfWidth * 3.0, 1e-9);
        }
    }
}

TEST(SkeletonBones, ALoneJointHasNoBone) {
    auto stage = open(R"(#usda 1.0
def Skeleton "Skel"
{
    uniform token[] joints = ["a"]
    uniform matrix4d[] bindTransforms = [((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,0,1))]
}
)",
                      "bones.usda");
    ASSERT_TRUE(stage);
    auto resolved = resolveSkeleton(*stage, *stage->find("/Skel"));
    ASSERT_TRUE(std::holds_alternative<Skinning>(resolved));
    EXPECT_EQ(boneCount(std::get<Skinning>(resolved)), 0u);
    EXPECT_TRUE(boneMesh(std::get<Skinning>(resolved), 0.0, nullptr).points.numbers.empty());
}

}  // namespace
}  // namespace obscura::usda::test
