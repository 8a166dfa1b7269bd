// Transforms (xformOpOrder, op kinds, inversion, resetXformStack, parents), sample times and
// visibility, checked against matrices worked out by hand in USD's row-vector convention.
#include <array>
#include <cmath>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using Matrix = std::array<double, 16>;

std::array<double, 3> transformPoint(const Matrix& m, std::array<double, 3> p) {
    std::array<double, 3> out{};
    for (int c = 0; c < 3; ++c) out[c] = p[0] * m[c] + p[1] * m[4 + c] + p[2] * m[8 + c] + m[12 + c];
    return out;
}

void expectMatrixNear(const Matrix& actual, const Matrix& expected) {
    for (size_t i = 0; i < 16; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-9) << "element " << i;
}

void expectPointNear(const std::array<double, 3>& actual, const std::array<double, 3>& expected) {
    for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-9) << "component " << i;
}

std::unique_ptr<Stage> stageWith(const std::string& body) {
    return test::open("#usda 1.0\n" + body);
}

TEST(Xform, FirstOpIsOutermost) {
    // [translate, rotateZ, scale]: points are scaled, then rotated, then translated: p * S * R * T.
    const auto stage = stageWith(R"(
def Xform "X"
{
    double3 xformOp:translate = (10, 0, 0)
    float xformOp:rotateZ = 90
    float3 xformOp:scale = (2, 2, 2)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateZ", "xformOp:scale"]
}
)");
    ASSERT_TRUE(stage);
    const Matrix local = stage->localTransform(*stage->find("/X"), 0);
    expectMatrixNear(local, {0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 10, 0, 0, 1});
    expectPointNear(transformPoint(local, {1, 0, 0}), {10, 2, 0});
}

TEST(Xform, RotateXYZAgainstHandComputedMatrices) {
    const auto stage = stageWith(R"(
def Xform "XYZ"
{
    float3 xformOp:rotateXYZ = (90, 90, 0)
    uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
}
def Xform "ZYX"
{
    float3 xformOp:rotateZYX = (90, 0, 90)
    uniform token[] xformOpOrder = ["xformOp:rotateZYX"]
}
def Xform "General"
{
    double3 xformOp:rotateXYZ = (30, 45, 60)
    uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
}
)");
    ASSERT_TRUE(stage);
    // Rx(90) * Ry(90): X first, then Y.
    expectMatrixNear(stage->localTransform(*stage->find("/XYZ"), 0),
                     {0, 0, -1, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 0, 1});
    // Rz(90) * Rx(90): the value still holds (x, y, z) angles.
    expectMatrixNear(stage->localTransform(*stage->find("/ZYX"), 0),
                     {0, 0, 1, 0, -1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 0, 1});
    // Rx(30) * Ry(45) * Rz(60) written out element by element.
    const double d = std::acos(-1.0) / 180.0;
    const double cx = std::cos(30 * d), sx = std::sin(30 * d);
    const double cy = std::cos(45 * d), sy = std::sin(45 * d);
    const double cz = std::cos(60 * d), sz = std::sin(60 * d);
    expectMatrixNear(stage->localTransform(*stage->find("/General"), 0),
                     {cy * cz, cy * sz, -sy, 0,
                      sx * sy * cz - cx * sz, sx * sy * sz + cx * cz, sx * cy, 0,
                      cx * sy * cz + sx * sz, cx * sy * sz - sx * cz, cx * cy, 0,
                      0, 0, 0, 1});
}

TEST(Xform, OrientAndTransformOps) {
    const auto stage = stageWith(R"(
def Xform "Orient"
{
    quatf xformOp:orient = (0.70710678, 0, 0, 0.70710678)
    uniform token[] xformOpOrder = ["xformOp:orient"]
}
def Xform "Matrix"
{
    matrix4d xformOp:transform = ((0, 1, 0, 0), (-1, 0, 0, 0), (0, 0, 1, 0), (1, 2, 3, 1))
    uniform token[] xformOpOrder = ["xformOp:transform"]
}
)");
    ASSERT_TRUE(stage);
    // 90 degrees about Z: X goes to Y.
    expectPointNear(transformPoint(stage->localTransform(*stage->find("/Orient"), 0), {1, 0, 0}), {0, 1, 0});
    expectMatrixNear(stage->localTransform(*stage->find("/Matrix"), 0),
                     {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1});
}

TEST(Xform, InvertedPivotOp) {
    // Rotating about a pivot at (1, 0, 0): the pivot stays, (2, 0, 0) swings to (1, 1, 0).
    const auto stage = stageWith(R"(
def Xform "X"
{
    float3 xformOp:translate:pivot = (1, 0, 0)
    float xformOp:rotateZ = 90
    uniform token[] xformOpOrder = ["xformOp:translate:pivot", "xformOp:rotateZ", "!invert!xformOp:translate:pivot"]
}
)");
    ASSERT_TRUE(stage);
    const Matrix local = stage->localTransform(*stage->find("/X"), 0);
    expectPointNear(transformPoint(local, {1, 0, 0}), {1, 0, 0});
    expectPointNear(transformPoint(local, {2, 0, 0}), {1, 1, 0});
}

const char* kHierarchy = R"(
def Xform "Parent"
{
    double3 xformOp:translate.timeSamples = { 0: (0, 0, 0), 10: (0, 0, 10) }
    float3 xformOp:scale = (2, 2, 2)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:scale"]
    token visibility.timeSamples = { 0: "inherited", 10: "invisible" }

    def Xform "Child"
    {
        double3 xformOp:translate = (1, 0, 0)
        float xformOp:rotateY.timeSamples = { 5: 0, 7: 90 }
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateY"]

        def Mesh "Leaf"
        {
        }
    }

    def Xform "Reset"
    {
        double3 xformOp:translate = (1, 0, 0)
        uniform token[] xformOpOrder = ["!resetXformStack!", "xformOp:translate"]
    }
}
def Xform "Hidden"
{
    token visibility = "invisible"

    def Mesh "Inside"
    {
    }
}
)";

TEST(Xform, WorldTransformGoesThroughParents) {
    const auto stage = stageWith(kHierarchy);
    ASSERT_TRUE(stage);
    const Prim& child = *stage->find("/Parent/Child");
    // Child origin: (1, 0, 0) in the parent, which scales by 2 then moves by (0, 0, t).
    expectPointNear(transformPoint(stage->worldTransform(child, 0), {0, 0, 0}), {2, 0, 0});
    expectPointNear(transformPoint(stage->worldTransform(child, 5), {0, 0, 0}), {2, 0, 5});
    // A prim without ops inherits its parent's world transform.
    const Matrix leaf = stage->worldTransform(*stage->find("/Parent/Child/Leaf"), 5);
    expectMatrixNear(leaf, stage->worldTransform(child, 5));
    // At time 7 the child also rotates 90 degrees about Y: +X turns to -Z, then scaled by 2.
    expectPointNear(transformPoint(stage->worldTransform(child, 7), {1, 0, 0}), {2, 0, 5});
}

TEST(Xform, AnimatedLocalTransformInterpolates) {
    const auto stage = stageWith(kHierarchy);
    ASSERT_TRUE(stage);
    const Matrix local = stage->localTransform(*stage->find("/Parent"), 2.5);
    EXPECT_NEAR(local[14], 2.5, 1e-12);
    EXPECT_NEAR(local[0], 2.0, 1e-12);
}

TEST(Xform, ResetXformStackIgnoresParents) {
    const auto stage = stageWith(kHierarchy);
    ASSERT_TRUE(stage);
    const Prim& reset = *stage->find("/Parent/Reset");
    bool resets = false;
    stage->localTransform(reset, 0, &resets);
    EXPECT_TRUE(resets);
    bool childResets = true;
    stage->localTransform(*stage->find("/Parent/Child"), 0, &childResets);
    EXPECT_FALSE(childResets);
    expectMatrixNear(stage->worldTransform(reset, 10), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1});
}

TEST(Xform, TransformSampleTimesUnionAncestorsUpToAReset) {
    const auto stage = stageWith(kHierarchy);
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->transformSampleTimes(*stage->find("/Parent/Child/Leaf")), (std::vector<double>{0, 5, 7, 10}));
    EXPECT_EQ(stage->transformSampleTimes(*stage->find("/Parent")), (std::vector<double>{0, 10}));
    EXPECT_TRUE(stage->transformSampleTimes(*stage->find("/Parent/Reset")).empty());
    EXPECT_TRUE(stage->transformSampleTimes(*stage->find("/Hidden")).empty());
}

TEST(Xform, VisibilityIsInherited) {
    const auto stage = stageWith(kHierarchy);
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->isVisible(*stage->find("/Hidden/Inside"), 0));
    EXPECT_FALSE(stage->isVisible(*stage->find("/Hidden"), 0));
    EXPECT_TRUE(stage->isVisible(*stage->find("/Parent/Child/Leaf"), 5));
    EXPECT_FALSE(stage->isVisible(*stage->find("/Parent/Child/Leaf"), 10));
}

TEST(Xform, VisibilityAnimatedOnAnAncestorIsSeenByItsDescendants) {
    const auto stage = stageWith(kHierarchy);
    ASSERT_TRUE(stage);
    EXPECT_TRUE(stage->hasAnimatedVisibility(*stage->find("/Parent/Child/Leaf")));
    EXPECT_FALSE(stage->hasAnimatedVisibility(*stage->find("/Hidden/Inside")));  // invisible, but not animated
}

// UsdGeomImageable::ComputePurpose: the prim's own opinion, else the nearest imageable ancestor's;
// a typeless ancestor (not imageable) passes nothing on.
TEST(Xform, PurposeIsTheNearestImageableOpinion) {
    const auto stage = stageWith(R"(
def Xform "Guides" {
    uniform token purpose = "guide"
    def Xform "Group" {
        def Mesh "Inherits" {}
        def Mesh "Own" {
            uniform token purpose = "render"
        }
    }
}
def "Typeless" {
    uniform token purpose = "proxy"
    def Mesh "Default" {}
}
)");
    ASSERT_TRUE(stage);
    auto purpose = [&](const char* path) {
        const Attribute* opinion = stage->purposeOpinion(*stage->find(path));
        return opinion ? opinion->defaultValue->strings.at(0) : std::string("default");
    };
    EXPECT_EQ(purpose("/Guides/Group/Inherits"), "guide");
    EXPECT_EQ(purpose("/Guides/Group/Own"), "render");
    EXPECT_EQ(purpose("/Typeless/Default"), "default");
}

TEST(Xform, NoOpsIsIdentity) {
    const auto stage = stageWith("def \"P\"\n{\n}\n");
    ASSERT_TRUE(stage);
    expectMatrixNear(stage->worldTransform(*stage->find("/P"), 0), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
}

}  // namespace
}  // namespace obscura::usda
