// USD mesh to triangles: validation, triangulation, winding and primvar interpolation.
#include "delegate/mesh_builder.h"

#include <gtest/gtest.h>

namespace obscura::delegate {
namespace {

MeshInput quadAndTriangle() {
    MeshInput m;
    m.points = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0};
    m.faceVertexCounts = {4, 3};
    m.faceVertexIndices = {0, 1, 2, 3, 1, 4, 2};
    return m;
}

TEST(MeshBuilder, FanTriangulatesPolygons) {
    auto built = buildMeshGeometry(quadAndTriangle());
    ASSERT_TRUE(std::holds_alternative<MeshGeometry>(built));
    const auto& g = std::get<MeshGeometry>(built);
    EXPECT_EQ(g.vertices.size(), 7u);
    EXPECT_EQ(g.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6}));
}

// Triangles come out group after group, each group's in face order; the vertices do not move.
TEST(MeshBuilder, FaceGroupsOrderTheTrianglesByGroup) {
    MeshInput m = quadAndTriangle();
    m.faceGroups = {2, 0};
    auto built = buildMeshGeometry(m);
    ASSERT_TRUE(std::holds_alternative<MeshGeometry>(built));
    const auto& g = std::get<MeshGeometry>(built);
    EXPECT_EQ(g.vertices.size(), 7u);
    EXPECT_EQ(g.indices, (std::vector<uint32_t>{4, 5, 6, 0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(g.groupRanges.size(), 3u);
    EXPECT_EQ(g.groupRanges[0].first, 0u);
    EXPECT_EQ(g.groupRanges[0].count, 3u);
    EXPECT_EQ(g.groupRanges[1].count, 0u) << "a group without faces";
    EXPECT_EQ(g.groupRanges[2].first, 3u);
    EXPECT_EQ(g.groupRanges[2].count, 6u);
}

TEST(MeshBuilder, WithoutFaceGroupsEveryTriangleIsInGroupZero) {
    auto built = buildMeshGeometry(quadAndTriangle());
    const auto& g = std::get<MeshGeometry>(built);
    ASSERT_EQ(g.groupRanges.size(), 1u);
    EXPECT_EQ(g.groupRanges[0].count, 9u);
}

TEST(MeshBuilder, LeftHandedFlipsWindingAndNormals) {
    MeshInput m = quadAndTriangle();
    m.leftHanded = true;
    auto built = buildMeshGeometry(m);
    const auto& g = std::get<MeshGeometry>(built);
    EXPECT_EQ((std::vector<uint32_t>(g.indices.begin(), g.indices.begin() + 3)), (std::vector<uint32_t>{0, 2, 1}));
    EXPECT_FLOAT_EQ(g.vertices[0].normal[2], -1.0f);
}

TEST(MeshBuilder, ComputedNormalsFollowTheRightHandRule) {
    auto built = buildMeshGeometry(quadAndTriangle());
    const auto& g = std::get<MeshGeometry>(built);
    for (const auto& v : g.vertices) EXPECT_FLOAT_EQ(v.normal[2], 1.0f);
}

TEST(MeshBuilder, PrimvarInterpolations) {
    MeshInput m = quadAndTriangle();
    m.displayColor = MeshPrimvar{{1, 0, 0, 0, 1, 0}, OBSCURA_INTERPOLATION_UNIFORM};
    auto g = std::get<MeshGeometry>(buildMeshGeometry(m));
    EXPECT_FLOAT_EQ(g.vertices[3].color[0], 1.0f);
    EXPECT_FLOAT_EQ(g.vertices[4].color[1], 1.0f);
    m.displayColor = MeshPrimvar{{0.25f, 0.5f, 0.75f}, OBSCURA_INTERPOLATION_CONSTANT};
    g = std::get<MeshGeometry>(buildMeshGeometry(m));
    for (const auto& v : g.vertices) EXPECT_FLOAT_EQ(v.color[2], 0.75f);
    std::vector<float> fv;
    for (int i = 0; i < 7; ++i) fv.insert(fv.end(), {float(i), 0, 0});
    m.displayColor = MeshPrimvar{fv, OBSCURA_INTERPOLATION_FACE_VARYING};
    g = std::get<MeshGeometry>(buildMeshGeometry(m));
    for (size_t i = 0; i < 7; ++i) EXPECT_FLOAT_EQ(g.vertices[i].color[0], float(i));
}

TEST(MeshBuilder, WrongPrimvarSizeIsDroppedWithAWarning) {
    MeshInput m = quadAndTriangle();
    m.normals = MeshPrimvar{{0, 0, 1, 0, 0, 1}, OBSCURA_INTERPOLATION_VERTEX};
    auto g = std::get<MeshGeometry>(buildMeshGeometry(m));
    ASSERT_EQ(g.warnings.size(), 1u);
    EXPECT_NE(g.warnings[0].find("normals"), std::string::npos);
}

TEST(MeshBuilder, RejectsBadTopology) {
    MeshInput m = quadAndTriangle();
    m.faceVertexIndices[6] = 5;
    EXPECT_NE(std::get<std::string>(buildMeshGeometry(m)).find("outside"), std::string::npos);
    m = quadAndTriangle();
    m.faceVertexCounts = {4, 2};
    EXPECT_TRUE(std::holds_alternative<std::string>(buildMeshGeometry(m)));
    m = quadAndTriangle();
    m.faceVertexCounts = {4, 4};
    EXPECT_NE(std::get<std::string>(buildMeshGeometry(m)).find("sum to 8"), std::string::npos);
    m = quadAndTriangle();
    m.faceVertexIndices[0] = -1;
    EXPECT_TRUE(std::holds_alternative<std::string>(buildMeshGeometry(m)));
}

}  // namespace
}  // namespace obscura::delegate
