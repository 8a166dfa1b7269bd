// Material subsets to face groups: which subset each face draws with, and what bad subsets say.
#include "delegate/material_subsets.h"

#include <gtest/gtest.h>

namespace obscura::delegate {
namespace {

TEST(FaceGroups, EachFaceTakesTheFirstSubsetThatListsIt) {
    MaterialSubsets subsets{{2, 2}, {3, 1, 1, 0}, {}, "unrestricted"};
    FaceGroups out = assignFaceGroups(subsets, 5, "/Mesh");
    EXPECT_EQ(out.groups, (std::vector<uint32_t>{2, 1, 0, 1, 0}));
    EXPECT_TRUE(out.warnings.empty());
}

TEST(FaceGroups, NoSubsetsNoGroups) {
    EXPECT_TRUE(assignFaceGroups(MaterialSubsets{}, 4, "/Mesh").groups.empty());
}

TEST(FaceGroups, BadIndicesAreIgnoredOneByOne) {
    MaterialSubsets subsets{{3}, {0, 9, -2}, {"/Mesh/Left"}, "nonOverlapping"};
    FaceGroups out = assignFaceGroups(subsets, 2, "/Mesh");
    EXPECT_EQ(out.groups, (std::vector<uint32_t>{1, 0}));
    EXPECT_EQ(out.warnings, (std::vector<std::string>{
                                "/Mesh/Left: indices[1] = 9 is outside the mesh's 2 faces; ignored",
                                "/Mesh/Left: indices[2] = -2 is outside the mesh's 2 faces; ignored"}));
}

TEST(FaceGroups, APartitionReportsOverlapsAndGaps) {
    MaterialSubsets subsets{{1, 1}, {0, 0}, {}, "partition"};
    FaceGroups out = assignFaceGroups(subsets, 2, "/Mesh");
    EXPECT_EQ(out.groups, (std::vector<uint32_t>{1, 0}));
    EXPECT_EQ(out.warnings,
              (std::vector<std::string>{"/Mesh: material subset 1: indices[0] = 0 is also in /Mesh: material subset 0, "
                                        "which a partition family forbids; the first keeps it",
                                        "/Mesh: subsetFamily:materialBind:familyType is partition but 1 of the 2 faces "
                                        "are in no material subset; they draw with material:binding"}));
}

TEST(FaceGroups, CountsThatDoNotFitDropEverySubset) {
    FaceGroups negative = assignFaceGroups(MaterialSubsets{{-1, 2}, {0}, {}, "unrestricted"}, 2, "/Mesh");
    EXPECT_TRUE(negative.groups.empty());
    EXPECT_EQ(negative.warnings,
              (std::vector<std::string>{"/Mesh: materialSubsets:faceCounts[0] is -1; material subsets ignored"}));
    FaceGroups unmatched = assignFaceGroups(MaterialSubsets{{2}, {0}, {}, "unrestricted"}, 2, "/Mesh");
    EXPECT_TRUE(unmatched.groups.empty());
    ASSERT_EQ(unmatched.warnings.size(), 1u);
}

}  // namespace
}  // namespace obscura::delegate
