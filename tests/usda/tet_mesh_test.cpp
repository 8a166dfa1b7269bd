// UsdGeomTetMesh's surface: two tets sharing a face have six surface faces, the shared one gone,
// each wound counter-clockwise seen from outside (its right-handed normal points away from the
// solid's centroid); authored surface faces win; bad indices are refused naming the attribute.
#include <gtest/gtest.h>

#include <array>
#include <set>

#include "harness/usda/tet_mesh.h"
#include "usda_test_util.h"

namespace obscura::usda::test {
namespace {

using Vec3 = std::array<double, 3>;

// A bipyramid: tet (0, 1, 2, 3) and tet (1, 2, 3, 4) share face (1, 2, 3); both positively
// oriented ((p3 - p0) . ((p1 - p0) x (p2 - p0)) > 0). It is convex, so every surface face's outward
// normal points away from the centroid of its points.
const std::vector<Vec3> kPoints = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
const std::vector<int> kTets = {0, 1, 2, 3, 1, 2, 3, 4};

Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

TEST(TetMesh, TwoTetsSharingAFaceHaveSixOutwardSurfaceFaces) {
    const std::vector<int> faces = tetSurfaceFaces(kTets);
    ASSERT_EQ(faces.size(), 6u * 3u);
    Vec3 centroid{0, 0, 0};
    for (const Vec3& p : kPoints)
        for (size_t c = 0; c < 3; ++c) centroid[c] += p[c] / double(kPoints.size());
    std::set<std::set<int>> seen;
    for (size_t f = 0; f < faces.size(); f += 3) {
        const Vec3 &a = kPoints[size_t(faces[f])], &b = kPoints[size_t(faces[f + 1])], &c = kPoints[size_t(faces[f + 2])];
        const Vec3 normal = cross(minus(b, a), minus(c, a));
        const Vec3 middle{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
        EXPECT_GT(dot(normal, minus(middle, centroid)), 0.0) << "face " << f / 3 << " faces inwards";
        seen.insert({faces[f], faces[f + 1], faces[f + 2]});
    }
    EXPECT_EQ(seen.size(), 6u);
    EXPECT_FALSE(seen.count({1, 2, 3})) << "the shared face is inside";
}

std::string tetStage(const std::string& extra) {
    return R"(#usda 1.0
def TetMesh "Tets"
{
    point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)]
    int4[] tetVertexIndices = [(0, 1, 2, 3), (1, 2, 3, 4)]
)" + extra + "}\n";
}

TEST(TetMesh, AuthoredSurfaceFacesWinAndBadIndicesAreNamed) {
    auto computed = open(tetStage(""));
    ASSERT_TRUE(computed);
    auto faces = tetMeshSurface(*computed->find("/Tets"), 0.0);
    ASSERT_TRUE(std::holds_alternative<std::vector<int>>(faces));
    EXPECT_EQ(std::get<std::vector<int>>(faces), tetSurfaceFaces(kTets));

    auto authored = open(tetStage("    int3[] surfaceFaceVertexIndices = [(0, 2, 1)]\n"));
    ASSERT_TRUE(authored);
    faces = tetMeshSurface(*authored->find("/Tets"), 0.0);
    ASSERT_TRUE(std::holds_alternative<std::vector<int>>(faces));
    EXPECT_EQ(std::get<std::vector<int>>(faces), (std::vector<int>{0, 2, 1}));

    auto outside = open(tetStage("    int3[] surfaceFaceVertexIndices = [(0, 2, 5)]\n"));
    ASSERT_TRUE(outside);
    faces = tetMeshSurface(*outside->find("/Tets"), 0.0);
    ASSERT_TRUE(std::holds_alternative<AttributeProblem>(faces));
    EXPECT_EQ(std::get<AttributeProblem>(faces).message, "surfaceFaceVertexIndices[0] names point 5, outside the 5 points");

    auto badTets = open(R"(#usda 1.0
def TetMesh "Tets"
{
    point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    int[] tetVertexIndices = [0, 1, 2, 3, 1, 2]
}
)");
    ASSERT_TRUE(badTets);
    faces = tetMeshSurface(*badTets->find("/Tets"), 0.0);
    ASSERT_TRUE(std::holds_alternative<AttributeProblem>(faces));
    EXPECT_EQ(std::get<AttributeProblem>(faces).attribute, "tetVertexIndices");
}

// Hydra keeps a TetMesh's primvars as authored on the mesh of its surface, so uniform ones hold one
// element per surface face and faceVarying ones one per surface face corner; per-tet counts (two
// tets, eight tet corners) do not fit and are named.
TEST(TetMesh, UniformAndFaceVaryingPrimvarsFitTheSurface) {
    auto stage = open(tetStage(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (0, 1, 1), (1, 0, 1)] (
        interpolation = "uniform"
    )
    float2[] primvars:st = [(0, 0), (1, 0), (0, 1), (0, 0), (1, 0), (0, 1), (0, 0), (1, 0), (0, 1),
                            (0, 0), (1, 0), (0, 1), (0, 0), (1, 0), (0, 1), (0, 0), (1, 0), (0, 1)] (
        interpolation = "faceVarying"
    )
    float[] primvars:perTet = [1, 2] (
        interpolation = "uniform"
    )
    float[] primvars:perTetCorner = [1, 2, 3, 4, 5, 6, 7, 8] (
        interpolation = "faceVarying"
    )
)"));
    ASSERT_TRUE(stage);
    const Prim& prim = *stage->find("/Tets");
    const auto surface = tetMeshSurface(prim, 0.0);
    ASSERT_TRUE(std::holds_alternative<std::vector<int>>(surface));
    const size_t faces = std::get<std::vector<int>>(surface).size() / 3;
    ASSERT_EQ(faces, 6u);
    auto problem = [&](const char* name, const char* interpolation, size_t elementSize = 1) {
        return tetSurfacePrimvarProblem(faces, prim.attribute(name)->evaluate(0.0)->size(), interpolation, elementSize);
    };
    EXPECT_EQ(problem("primvars:displayColor", "uniform"), "");
    EXPECT_EQ(problem("primvars:st", "faceVarying"), "");
    EXPECT_EQ(problem("primvars:perTet", "uniform"), "2 values but uniform interpolation needs 6 (one per surface face)");
    EXPECT_EQ(problem("primvars:perTetCorner", "faceVarying"),
              "8 values but faceVarying interpolation needs 18 (one per surface face corner)");
    // Two values to an element: twelve for the six faces.
    EXPECT_EQ(problem("primvars:displayColor", "uniform", 2),
              "6 values but uniform interpolation needs 12 (one per surface face)");
}

}  // namespace
}  // namespace obscura::usda::test
