// UsdSkel: bindings resolved and points skinned by linear blend skinning, checked against what the
// UsdSkel schema says a two-joint arm does when its elbow bends (positions worked out by hand),
// bad skinning data reported with where it is authored, and the corpus's skinned, animated figure
// (RiggedSimple.usdz, a glTF sample converted by others) posed at two times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "harness/usda/skinning.h"
#include "usda_test_util.h"

namespace obscura::usda::test {
namespace {

// An arm along +X: joint "root" at the origin, joint "root/elbow" at x = 1 (skeleton space). The
// animation bends the elbow about +Z from 0 degrees at time 0 to 90 degrees at time 1. The
// skeleton is lifted 10 up, the skinned mesh is placed 100 along X: skinned points follow the
// skeleton, the mesh's own transform cancels (UsdSkelImaging: skel space -> world -> prim space).
std::string rig(const std::string& influences, const std::string& extraMesh = "") {
    return R"(#usda 1.0
def SkelRoot "Rig"
{
    def Skeleton "Skel" (
        prepend apiSchemas = ["SkelBindingAPI"]
    )
    {
        uniform token[] joints = ["root", "root/elbow"]
        uniform matrix4d[] bindTransforms = [((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,0,1)), ((1,0,0,0),(0,1,0,0),(0,0,1,0),(1,0,0,1))]
        uniform matrix4d[] restTransforms = [((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,0,1)), ((1,0,0,0),(0,1,0,0),(0,0,1,0),(1,0,0,1))]
        rel skel:animationSource = </Rig/Skel/Anim>
        double3 xformOp:translate = (0, 10, 0)
        uniform token[] xformOpOrder = ["xformOp:translate"]

        def SkelAnimation "Anim"
        {
            uniform token[] joints = ["root", "root/elbow"]
            float3[] translations = [(0, 0, 0), (1, 0, 0)]
            quatf[] rotations.timeSamples = {
                0: [(1, 0, 0, 0), (1, 0, 0, 0)],
                1: [(1, 0, 0, 0), (0.70710678, 0, 0, 0.70710678)],
            }
            half3[] scales = [(1, 1, 1), (1, 1, 1)]
        }
    }

    def Mesh "Arm" (
        prepend apiSchemas = ["SkelBindingAPI"]
    )
    {
        rel skel:skeleton = </Rig/Skel>
        point3f[] points = [(0.5, 0, 0), (2, 0, 0), (1.5, 0, 0)]
        int[] faceVertexCounts = [3]
        int[] faceVertexIndices = [0, 1, 2]
        double3 xformOp:translate = (100, 0, 0)
        uniform token[] xformOpOrder = ["xformOp:translate"]
)" + influences + extraMesh +
           R"(
    }
}
)";
}

// Point 0 follows the root, point 1 the elbow, point 2 both halves each.
const char* kVertexInfluences = R"(
        int[] primvars:skel:jointIndices = [0, 1, 1, 0, 0, 1] (
            interpolation = "vertex"
            elementSize = 2
        )
        float[] primvars:skel:jointWeights = [1, 0, 1, 0, 0.5, 0.5] (
            interpolation = "vertex"
            elementSize = 2
        )
)";

// World positions of the skinned points of /Rig/Arm at `time` (the host draws the points it is
// served with the mesh's own transform, here +100 along X).
std::vector<double> skinnedWorld(const Stage& stage, double time, std::string* problem = nullptr) {
    const Prim* arm = stage.find("/Rig/Arm");
    auto skinning = resolveSkinning(stage, *arm);
    EXPECT_TRUE(skinning && std::holds_alternative<Skinning>(*skinning));
    if (!skinning || !std::holds_alternative<Skinning>(*skinning)) return {};
    std::vector<double> points = skinPoints(stage, std::get<Skinning>(*skinning),
                                            arm->attribute("points")->evaluate(time)->numbers, time, problem);
    for (size_t i = 0; i < points.size(); i += 3) points[i] += 100.0;
    return points;
}

void expectPoint(const std::vector<double>& points, size_t i, double x, double y, double z) {
    ASSERT_GE(points.size(), 3 * i + 3);
    EXPECT_NEAR(points[3 * i], x, 1e-6) << "point " << i;
    EXPECT_NEAR(points[3 * i + 1], y, 1e-6) << "point " << i;
    EXPECT_NEAR(points[3 * i + 2], z, 1e-6) << "point " << i;
}

TEST(Skinning, TheBindPoseLeavesPointsWhereTheSkeletonIs) {
    auto stage = open(rig(kVertexInfluences));
    ASSERT_TRUE(stage);
    auto points = skinnedWorld(*stage, 0.0);
    expectPoint(points, 0, 0.5, 10, 0);
    expectPoint(points, 1, 2, 10, 0);
    expectPoint(points, 2, 1.5, 10, 0);
}

TEST(Skinning, ABentElbowMovesPointsWhereLinearBlendSkinningSays) {
    auto stage = open(rig(kVertexInfluences));
    ASSERT_TRUE(stage);
    auto points = skinnedWorld(*stage, 1.0);
    // The elbow's point, 1 beyond the elbow along X, swings 90 degrees about Z to 1 above it.
    expectPoint(points, 1, 1, 11, 0);
    // The root's point does not move.
    expectPoint(points, 0, 0.5, 10, 0);
    // Half and half: the mean of (1.5, 0) moved by the root and (1, 0.5) moved by the elbow.
    expectPoint(points, 2, 1.25, 10.25, 0);
}

TEST(Skinning, TimeSamplesOfRotationsAreSlerped) {
    auto stage = open(rig(kVertexInfluences));
    ASSERT_TRUE(stage);
    auto points = skinnedWorld(*stage, 0.5);
    const double c = std::cos(M_PI / 4), s = std::sin(M_PI / 4);
    expectPoint(points, 1, 1 + c, 10 + s, 0);
}

TEST(Skinning, ConstantInfluencesAndTheirOwnJointOrder) {
    // skel:joints on the mesh: index 0 names the elbow. Constant: every point follows it.
    auto stage = open(rig(R"(
        uniform token[] skel:joints = ["root/elbow"]
        int[] primvars:skel:jointIndices = [0] (interpolation = "constant")
        float[] primvars:skel:jointWeights = [1] (interpolation = "constant")
)"));
    ASSERT_TRUE(stage);
    auto points = skinnedWorld(*stage, 1.0);
    expectPoint(points, 0, 1, 9.5, 0);  // (0.5, 0) is 0.5 before the elbow: swings to 0.5 below it
    expectPoint(points, 1, 1, 11, 0);
}

TEST(Skinning, GeomBindTransformTakesPointsToBindSpaceFirst) {
    // The mesh was bound while lying 1 lower: its bind transform lifts it by 1 first.
    auto stage = open(rig(kVertexInfluences, R"(
        matrix4d primvars:skel:geomBindTransform = ((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,1,0,1))
)"));
    ASSERT_TRUE(stage);
    auto points = skinnedWorld(*stage, 1.0);
    // (2, 1) relative to the elbow (1, 0) is (1, 1); 90 degrees about Z: (-1, 1).
    expectPoint(points, 1, 0, 11, 0);
}

TEST(Skinning, NormalsTurnWithTheirJoints) {
    auto stage = open(rig(kVertexInfluences));
    ASSERT_TRUE(stage);
    const Prim* arm = stage->find("/Rig/Arm");
    auto skinning = resolveSkinning(*stage, *arm);
    ASSERT_TRUE(skinning && std::holds_alternative<Skinning>(*skinning));
    const std::vector<double> up = {0, 1, 0, 0, 1, 0, 0, 1, 0};
    std::string problem;
    // One normal per point: the elbow's turns 90 degrees about Z, the shared one is the blend of
    // both (as UsdSkelImaging's skinNormalsLBS, unnormalized).
    auto normals = skinNormals(*stage, std::get<Skinning>(*skinning), up, nullptr, 3, 1.0, &problem);
    EXPECT_EQ(problem, "");
    expectPoint(normals, 0, 0, 1, 0);
    expectPoint(normals, 1, -1, 0, 0);
    expectPoint(normals, 2, -0.5, 0.5, 0);
    // Face-varying: each face-vertex's normal follows the point it belongs to.
    const std::vector<double> faceVertices = {1, 0, 2};
    normals = skinNormals(*stage, std::get<Skinning>(*skinning), up, &faceVertices, 3, 1.0, &problem);
    expectPoint(normals, 0, -1, 0, 0);
    expectPoint(normals, 1, 0, 1, 0);
    expectPoint(normals, 2, -0.5, 0.5, 0);
}

TEST(Skinning, BlendShapesMovePointsByTheirWeightBeforeTheJoints) {
    // "reach" moves point 1 (sparse: pointIndices) 1 further along X; "lift" moves every point up
    // by 0.5 (dense). The animation names them in its own order and weighs them 0 at time 0,
    // lift 1 and reach 0.5 at time 1, when the elbow is bent.
    std::string text = rig(kVertexInfluences, R"(
        uniform token[] skel:blendShapes = ["reach", "lift"]
        rel skel:blendShapeTargets = [</Rig/Arm/Reach>, </Rig/Arm/Lift>]
        def BlendShape "Reach"
        {
            uniform vector3f[] offsets = [(1, 0, 0)]
            uniform int[] pointIndices = [1]
        }
        def BlendShape "Lift"
        {
            uniform vector3f[] offsets = [(0, 0.5, 0), (0, 0.5, 0), (0, 0.5, 0)]
        }
)");
    const std::string scales = "half3[] scales = [(1, 1, 1), (1, 1, 1)]";
    text.replace(text.find(scales), scales.size(),
                 scales + "\n            uniform token[] blendShapes = [\"lift\", \"reach\"]\n"
                          "            float[] blendShapeWeights.timeSamples = {\n"
                          "                0: [0, 0],\n                1: [1, 0.5],\n            }");
    auto stage = open(text);
    ASSERT_TRUE(stage);
    auto rest = skinnedWorld(*stage, 0.0);
    expectPoint(rest, 1, 2, 10, 0);
    auto points = skinnedWorld(*stage, 1.0);
    // Point 0: lifted, on the root. Point 1: (2.5, 0.5) shaped, 1.5 beyond and 0.5 above the
    // elbow, turned 90 degrees about Z to 0.5 before and 1.5 above it. Point 2: (1.5, 0.5) shaped,
    // halfway between the root's (1.5, 0.5) and the elbow's (0.5, 0.5).
    expectPoint(points, 0, 0.5, 10.5, 0);
    expectPoint(points, 1, 0.5, 11.5, 0);
    expectPoint(points, 2, 1.0, 10.5, 0);
}

TEST(Skinning, BlendShapeIndicesOutsideThePointsAreReported) {
    std::string text = rig(kVertexInfluences, R"(
        uniform token[] skel:blendShapes = ["reach"]
        rel skel:blendShapeTargets = </Rig/Arm/Reach>
        def BlendShape "Reach"
        {
            uniform vector3f[] offsets = [(1, 0, 0)]
            uniform int[] pointIndices = [9]
        }
)");
    const std::string scales = "half3[] scales = [(1, 1, 1), (1, 1, 1)]";
    text.replace(text.find(scales), scales.size(),
                 scales + "\n            uniform token[] blendShapes = [\"reach\"]\n"
                          "            float[] blendShapeWeights = [1]");
    auto stage = open(text);
    ASSERT_TRUE(stage);
    std::string problem;
    EXPECT_TRUE(skinnedWorld(*stage, 1.0, &problem).empty());
    EXPECT_EQ(problem, "blend shape \"reach\" moves point 9, outside the 3 points");
}

// A problem with skinning data, with where it is authored.
SkinningProblem problemOf(const std::string& influences, const std::string& file = "bad_skin.usda") {
    auto result = Stage::openFromString(rig(influences), file);
    EXPECT_TRUE(std::holds_alternative<std::unique_ptr<Stage>>(result));
    const Stage& stage = *std::get<std::unique_ptr<Stage>>(result);
    auto skinning = resolveSkinning(stage, *stage.find("/Rig/Arm"));
    EXPECT_TRUE(skinning && std::holds_alternative<SkinningProblem>(*skinning));
    if (!skinning || !std::holds_alternative<SkinningProblem>(*skinning)) return {};
    return std::get<SkinningProblem>(*skinning);
}

// The line (1-based) of `text` in the rig with `influences`.
int lineOf(const std::string& influences, const std::string& text) {
    const std::string file = rig(influences);
    const size_t at = file.find(text);
    EXPECT_NE(at, std::string::npos);
    return int(std::count(file.begin(), file.begin() + long(at), '\n')) + 1;
}

TEST(Skinning, AJointIndexOutOfRangeIsReportedWhereItIsAuthored) {
    const std::string influences = R"(
        int[] primvars:skel:jointIndices = [0, 1, 1, 0, 0, 5] (
            interpolation = "vertex"
            elementSize = 2
        )
        float[] primvars:skel:jointWeights = [1, 0, 1, 0, 0.5, 0.5] (
            interpolation = "vertex"
            elementSize = 2
        )
)";
    SkinningProblem problem = problemOf(influences);
    EXPECT_NE(problem.message.find("jointIndices[5] = 5 is outside the 2 joints"), std::string::npos) << problem.message;
    EXPECT_EQ(problem.where.file, "bad_skin.usda");
    EXPECT_EQ(problem.where.line, lineOf(influences, "int[] primvars:skel:jointIndices"));
    EXPECT_GT(problem.where.column, 0);
}

TEST(Skinning, WeightsThatDoNotMatchTheIndicesAreReported) {
    const std::string influences = R"(
        int[] primvars:skel:jointIndices = [0, 1, 1, 0, 0, 1] (
            interpolation = "vertex"
            elementSize = 2
        )
        float[] primvars:skel:jointWeights = [1, 0, 1, 0, 0.5] (
            interpolation = "vertex"
            elementSize = 2
        )
)";
    SkinningProblem problem = problemOf(influences);
    EXPECT_NE(problem.message.find("jointWeights has 5 values but jointIndices has 6"), std::string::npos)
        << problem.message;
    EXPECT_EQ(problem.where.line, lineOf(influences, "float[] primvars:skel:jointWeights"));
}

TEST(Skinning, InfluencesThatDoNotCoverThePointsAreReportedWhenSkinning) {
    auto stage = open(rig(R"(
        int[] primvars:skel:jointIndices = [0, 1, 1, 0] (
            interpolation = "vertex"
            elementSize = 2
        )
        float[] primvars:skel:jointWeights = [1, 0, 1, 0] (
            interpolation = "vertex"
            elementSize = 2
        )
)"));
    ASSERT_TRUE(stage);
    std::string problem;
    EXPECT_TRUE(skinnedWorld(*stage, 1.0, &problem).empty());
    EXPECT_NE(problem.find("needs 6 (3 points)"), std::string::npos) << problem;
}

TEST(Skinning, ABindingOutsideASkelRootIsNoSkinning) {
    std::string text = rig(kVertexInfluences);
    text.replace(text.find("SkelRoot"), 8, "Xform");
    auto stage = open(text);
    ASSERT_TRUE(stage);
    auto skinning = resolveSkinning(*stage, *stage->find("/Rig/Arm"));
    ASSERT_TRUE(skinning && std::holds_alternative<SkinningProblem>(*skinning));
    EXPECT_NE(std::get<SkinningProblem>(*skinning).message.find("not beneath a SkelRoot"), std::string::npos);
}

TEST(Skinning, APrimWithoutInfluencesIsNotSkinned) {
    auto stage = open(rig(""));
    ASSERT_TRUE(stage);
    EXPECT_FALSE(resolveSkinning(*stage, *stage->find("/Rig/Arm")));
}

// ---- The corpus ------------------------------------------------------------------------------

const std::filesystem::path kRigged =
    std::filesystem::path(OBSCURA_CORPUS_DIR) / "test_assets/USDZ/RiggedSimple/RiggedSimple.usdz";
const char* kCylinder = "/RiggedSimple/Geom/Z_UP/Armature/Bone_3/Cylinder_2";

struct Bounds {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    void extend(const double* p) {
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], p[c]), hi[c] = std::max(hi[c], p[c]);
    }
};

// `points` (xyz, a prim's own space) through `m` into world space.
Bounds boundsOf(const std::vector<double>& points, const matrix4::Matrix4& m) {
    Bounds b;
    for (size_t i = 0; i + 2 < points.size(); i += 3) {
        double w[3];
        for (int c = 0; c < 3; ++c)
            w[c] = points[i] * m[size_t(c)] + points[i + 1] * m[size_t(4 + c)] + points[i + 2] * m[size_t(8 + c)] +
                   m[size_t(12 + c)];
        b.extend(w);
    }
    return b;
}

// The cylinder's skinned points at `time` and their world bounds.
Bounds skinnedBounds(const Stage& stage, double time) {
    const Prim& cylinder = *stage.find(kCylinder);
    auto skinning = resolveSkinning(stage, cylinder);
    EXPECT_TRUE(skinning && std::holds_alternative<Skinning>(*skinning));
    if (!skinning || !std::holds_alternative<Skinning>(*skinning)) return {};
    std::string problem;
    auto points = skinPoints(stage, std::get<Skinning>(*skinning), cylinder.attribute("points")->evaluate(time)->numbers,
                             time, &problem);
    EXPECT_EQ(problem, "");
    return boundsOf(points, stage.worldTransform(cylinder, time));
}

TEST(SkinningCorpus, RiggedSimpleIsSkinnedAndMovesOverItsFrames) {
    if (!std::filesystem::exists(kRigged)) GTEST_SKIP() << "no corpus at " << kRigged;
    auto stage = openFile(kRigged.string());
    ASSERT_TRUE(stage);
    // At its first frame the animation poses the elbow joint as it rests relative to the root
    // (restTransforms), so the whole cylinder moves rigidly with the root joint: the rest points
    // through the root's inverse bind transform (its animated pose is the identity), no blending.
    const Prim& cylinder = *stage->find(kCylinder);
    const Prim& skeleton = *stage->find("/RiggedSimple/Geom/Z_UP/Armature/Bone_3/Skeleton");
    auto bind = skeleton.attribute("bindTransforms")->evaluate(0)->numbers;
    matrix4::Matrix4 rootBind;
    std::copy_n(bind.begin(), 16, rootBind.begin());
    auto rest = cylinder.attribute("points")->evaluate(1)->numbers;
    const Bounds rigid = boundsOf(rest, matrix4::multiply(matrix4::inverse(rootBind), stage->worldTransform(skeleton, 1)));
    const Bounds first = skinnedBounds(*stage, 1);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(first.lo[c], rigid.lo[c], 1e-3) << "axis " << c;
        EXPECT_NEAR(first.hi[c], rigid.hi[c], 1e-3) << "axis " << c;
    }
    // Mid-animation the elbow bends: the cylinder (radius 1) reaches beyond its straight self.
    const Bounds middle = skinnedBounds(*stage, 25);
    EXPECT_GT(middle.hi[0] - first.hi[0], 1.0);
    // The last frame closes the loop where the first began.
    const Bounds last = skinnedBounds(*stage, 50);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(last.hi[c], first.hi[c], 1e-3) << "axis " << c;
}

}  // namespace
}  // namespace obscura::usda::test
