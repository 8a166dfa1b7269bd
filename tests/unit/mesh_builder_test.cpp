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
    // The triangle shares points 1 and 2 with the quad, and with smooth normals their vertices.
    auto built = buildMeshGeometry(quadAndTriangle());
    ASSERT_TRUE(std::holds_alternative<MeshGeometry>(built));
    const auto& g = std::get<MeshGeometry>(built);
    EXPECT_EQ(g.vertices.size(), 5u);
    EXPECT_EQ(g.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 1, 4, 2}));
}

// A 2x2 grid of quads: 16 face-vertices on 9 points. With per-point values they are 9 vertices;
// a face-varying st seam down the middle column splits its 3 points in two (12); uniform colours
// split every point by the faces around it (16).
TEST(MeshBuilder, FaceVerticesOfOneVertexAreWelded) {
    MeshInput m;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) m.points.insert(m.points.end(), {float(x), float(y), 0.0f});
    m.faceVertexCounts = {4, 4, 4, 4};
    m.faceVertexIndices = {0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7};
    auto g = std::get<MeshGeometry>(buildMeshGeometry(m));
    EXPECT_EQ(g.vertices.size(), 9u);
    EXPECT_EQ(g.indices.size(), 24u);
    for (uint32_t i : g.indices) {
        ASSERT_LT(i, g.vertices.size());
    }
    // Each triangle's corners are the points its face names, in order.
    for (size_t t = 0; t < 8; ++t) {
        const size_t face = t / 2, corner[3] = {0, t % 2 + 1, t % 2 + 2};
        for (size_t k = 0; k < 3; ++k) {
            const size_t p = size_t(m.faceVertexIndices[4 * face + corner[k]]);
            EXPECT_EQ(g.vertices[g.indices[3 * t + k]].position[0], m.points[3 * p]) << "triangle " << t;
            EXPECT_EQ(g.vertices[g.indices[3 * t + k]].position[1], m.points[3 * p + 1]) << "triangle " << t;
        }
    }
    // st: u = x, except that the right-hand faces see the middle column at u = 5 (a seam).
    std::vector<float> st;
    for (size_t fv = 0; fv < m.faceVertexIndices.size(); ++fv) {
        const int p = m.faceVertexIndices[fv];
        const bool rightFace = fv / 4 == 1 || fv / 4 == 3;
        st.insert(st.end(), {rightFace && p % 3 == 1 ? 5.0f : float(p % 3), float(p / 3)});
    }
    m.st = MeshPrimvar{st, OBSCURA_INTERPOLATION_FACE_VARYING, 2};
    EXPECT_EQ(std::get<MeshGeometry>(buildMeshGeometry(m)).vertices.size(), 12u);
    m.st.reset();
    m.displayColor = MeshPrimvar{{1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0}, OBSCURA_INTERPOLATION_UNIFORM, 3};
    EXPECT_EQ(std::get<MeshGeometry>(buildMeshGeometry(m)).vertices.size(), 16u);
}

// Triangles come out group after group, each group's in face order; the vertices do not move.
TEST(MeshBuilder, FaceGroupsOrderTheTrianglesByGroup) {
    MeshInput m = quadAndTriangle();
    m.faceGroups = {2, 0};
    auto built = buildMeshGeometry(m);
    ASSERT_TRUE(std::holds_alternative<MeshGeometry>(built));
    const auto& g = std::get<MeshGeometry>(built);
    EXPECT_EQ(g.vertices.size(), 5u);
    EXPECT_EQ(g.indices, (std::vector<uint32_t>{1, 4, 2, 0, 1, 2, 0, 2, 3}));
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
