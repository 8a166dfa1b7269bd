// Subdivision surfaces through OpenSubdiv: face counts, limit normals, handedness, creases,
// corners, holes, boundaries, primvars, topology caching and rejected input.
#include "delegate/subdivision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace obscura::delegate {
namespace {

using V3 = std::array<float, 3>;

V3 pointAt(const std::vector<float>& values, size_t i) { return {values[3 * i], values[3 * i + 1], values[3 * i + 2]}; }
V3 minus(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
float length(V3 v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
float dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The cube [-1, 1]^3 with every face counter-clockwise seen from outside (right-handed).
MeshInput cube() {
    MeshInput m;
    m.points = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1};
    m.faceVertexCounts = {4, 4, 4, 4, 4, 4};
    m.faceVertexIndices = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 3, 7, 6, 2, 0, 4, 7, 3, 1, 2, 6, 5};
    return m;
}

// The same cube authored left-handed: each face's winding reversed (first vertex kept).
MeshInput leftHandedCube() {
    MeshInput m = cube();
    m.leftHanded = true;
    for (size_t base = 0; base < m.faceVertexIndices.size(); base += 4)
        std::reverse(m.faceVertexIndices.begin() + long(base) + 1, m.faceVertexIndices.begin() + long(base) + 4);
    return m;
}

// A tetrahedron with outward counter-clockwise triangles.
MeshInput tetrahedron() {
    MeshInput m;
    m.points = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
    m.faceVertexCounts = {3, 3, 3, 3};
    m.faceVertexIndices = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
    return m;
}

// An open 3 x 3 grid of unit quads in the z = 0 plane, 4 x 4 points.
MeshInput quadGrid() {
    MeshInput m;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) m.points.insert(m.points.end(), {float(x), float(y), 0.0f});
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            const int v = 4 * y + x;
            m.faceVertexCounts.push_back(4);
            m.faceVertexIndices.insert(m.faceVertexIndices.end(), {v, v + 1, v + 5, v + 4});
        }
    return m;
}

MeshInput refined(const MeshInput& mesh, SubdivisionScheme scheme, int level, const SubdivisionTags& tags = {}) {
    auto result = refineMesh(mesh, scheme, tags, level);
    if (const auto* error = std::get_if<std::string>(&result)) ADD_FAILURE() << *error;
    return std::holds_alternative<MeshInput>(result) ? std::get<MeshInput>(result) : MeshInput{};
}

bool hasPoint(const MeshInput& mesh, V3 p, float tolerance = 1e-5f) {
    for (size_t i = 0; i < mesh.points.size() / 3; ++i) {
        if (length(minus(pointAt(mesh.points, i), p)) < tolerance) return true;
    }
    return false;
}

bool hasAllCubeCorners(const MeshInput& mesh) {
    const MeshInput control = cube();
    for (size_t i = 0; i < 8; ++i)
        if (!hasPoint(mesh, pointAt(control.points, i))) return false;
    return true;
}

// Points that some face uses (hole faces leave theirs unused).
std::vector<size_t> usedPoints(const MeshInput& mesh) {
    std::vector<size_t> used(mesh.faceVertexIndices.begin(), mesh.faceVertexIndices.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    return used;
}

void expectOutwardNormals(const MeshInput& mesh) {
    ASSERT_TRUE(mesh.normals.has_value());
    EXPECT_EQ(mesh.normals->interpolation, OBSCURA_INTERPOLATION_VERTEX);
    ASSERT_EQ(mesh.normals->values.size(), mesh.points.size());
    for (size_t i : usedPoints(mesh)) {
        const V3 n = pointAt(mesh.normals->values, i);
        EXPECT_NEAR(length(n), 1.0f, 1e-4f) << "point " << i;
        EXPECT_GT(dot(n, pointAt(mesh.points, i)), 0.0f) << "point " << i;  // the centre is the origin
    }
}

TEST(Subdivision, ParsesUsdSchemeTokens) {
    EXPECT_EQ(parseSubdivisionScheme("catmullClark"), SubdivisionScheme::CatmullClark);
    EXPECT_EQ(parseSubdivisionScheme("loop"), SubdivisionScheme::Loop);
    EXPECT_EQ(parseSubdivisionScheme("bilinear"), SubdivisionScheme::Bilinear);
    EXPECT_EQ(parseSubdivisionScheme("none"), SubdivisionScheme::None);
}

TEST(Subdivision, CatmullClarkCubeQuadruplesItsQuadsPerLevel) {
    const MeshInput one = refined(cube(), SubdivisionScheme::CatmullClark, 1);
    EXPECT_EQ(one.faceVertexCounts, std::vector<int32_t>(24, 4));
    EXPECT_EQ(one.points.size() / 3, 26u);  // 8 corners + 12 edge points + 6 face points
    EXPECT_EQ(one.faceVertexIndices.size(), 96u);
    const MeshInput two = refined(cube(), SubdivisionScheme::CatmullClark, 2);
    EXPECT_EQ(two.faceVertexCounts, std::vector<int32_t>(96, 4));
}

TEST(Subdivision, CatmullClarkCubeShrinksInsideSymmetrically) {
    // A valence-3 corner moves to (F + 2R) / 3 = (1/3 + 2 * 2/3) / 3 = 5/9 per coordinate.
    EXPECT_TRUE(hasPoint(refined(cube(), SubdivisionScheme::CatmullClark, 1), {5.0f / 9, 5.0f / 9, 5.0f / 9}));

    const MeshInput m = refined(cube(), SubdivisionScheme::CatmullClark, 3);
    for (float c : m.points) EXPECT_LT(std::abs(c), 1.0f);
    // The corner-most point towards each of the 8 cube corners: all on the diagonals, all at one
    // distance from the centre.
    std::vector<float> distances;
    for (float sx : {-1.0f, 1.0f})
        for (float sy : {-1.0f, 1.0f})
            for (float sz : {-1.0f, 1.0f}) {
                const V3 direction{sx, sy, sz};
                size_t best = 0;
                for (size_t i = 1; i < m.points.size() / 3; ++i)
                    if (dot(pointAt(m.points, i), direction) > dot(pointAt(m.points, best), direction)) best = i;
                const V3 p = pointAt(m.points, best);
                EXPECT_NEAR(p[0] * sx, p[1] * sy, 1e-6f);
                EXPECT_NEAR(p[0] * sx, p[2] * sz, 1e-6f);
                distances.push_back(length(p));
            }
    for (float distance : distances) EXPECT_NEAR(distance, distances[0], 1e-6f);
}

TEST(Subdivision, LimitNormalsPointOutward) {
    MeshInput m = cube();
    // Authored normals do not apply to a subdivision surface: these inward ones must be replaced.
    m.normals = MeshPrimvar{std::vector<float>(24, 0.0f), OBSCURA_INTERPOLATION_VERTEX};
    for (size_t i = 0; i < 24; ++i) m.normals->values[i] = -m.points[i];
    const MeshInput out = refined(m, SubdivisionScheme::CatmullClark, 2);
    EXPECT_FALSE(out.leftHanded);
    expectOutwardNormals(out);
}

TEST(Subdivision, LeftHandedCubeGivesTheSameOutwardSurface) {
    const MeshInput right = refined(cube(), SubdivisionScheme::CatmullClark, 2);
    const MeshInput left = refined(leftHandedCube(), SubdivisionScheme::CatmullClark, 2);
    EXPECT_FALSE(left.leftHanded);  // faces come out counter-clockwise
    expectOutwardNormals(left);
    ASSERT_EQ(left.points.size(), right.points.size());
    for (size_t i = 0; i < left.points.size(); ++i) EXPECT_NEAR(left.points[i], right.points[i], 1e-6f);
    EXPECT_EQ(left.faceVertexIndices, right.faceVertexIndices);
}

// The 12 cube edges as creases of 2 vertices each.
SubdivisionTags creasedEdges(float sharpness) {
    SubdivisionTags tags;
    tags.creaseIndices = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7};
    tags.creaseLengths.assign(12, 2);
    tags.creaseSharpnesses.assign(12, sharpness);
    return tags;
}

TEST(Subdivision, InfinitelySharpCreasesKeepTheCorners) {
    EXPECT_FALSE(hasAllCubeCorners(refined(cube(), SubdivisionScheme::CatmullClark, 2)));
    EXPECT_TRUE(hasAllCubeCorners(refined(cube(), SubdivisionScheme::CatmullClark, 2, creasedEdges(10.0f))));
    EXPECT_FALSE(hasAllCubeCorners(refined(cube(), SubdivisionScheme::CatmullClark, 2, creasedEdges(0.0f))));
    expectOutwardNormals(refined(cube(), SubdivisionScheme::CatmullClark, 2, creasedEdges(10.0f)));
}

TEST(Subdivision, CreaseRunsTakeOneSharpnessPerRunOrPerEdge) {
    // The same 12 edges as 6 runs: two loops of 5 vertices (4 edges each) and 4 vertical edges.
    SubdivisionTags perRun;
    perRun.creaseIndices = {0, 1, 2, 3, 0, 4, 5, 6, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7};
    perRun.creaseLengths = {5, 5, 2, 2, 2, 2};
    perRun.creaseSharpnesses.assign(6, 10.0f);
    const MeshInput byRun = refined(cube(), SubdivisionScheme::CatmullClark, 2, perRun);
    EXPECT_TRUE(hasAllCubeCorners(byRun));

    SubdivisionTags perEdge = perRun;
    perEdge.creaseSharpnesses.assign(12, 10.0f);
    const MeshInput byEdge = refined(cube(), SubdivisionScheme::CatmullClark, 2, perEdge);
    EXPECT_EQ(byEdge.points, byRun.points);

    // Per edge, only the bottom loop's 4 edges sharp: the bottom stays flat at z = -1 while the
    // top rounds off (read per run, the second value would sharpen the top loop too).
    perEdge.creaseSharpnesses.assign(12, 0.0f);
    std::fill_n(perEdge.creaseSharpnesses.begin(), 4, 10.0f);
    const MeshInput bottomOnly = refined(cube(), SubdivisionScheme::CatmullClark, 2, perEdge);
    float minZ = 0.0f, maxZ = 0.0f;
    for (size_t i = 2; i < bottomOnly.points.size(); i += 3) {
        minZ = std::min(minZ, bottomOnly.points[i]);
        maxZ = std::max(maxZ, bottomOnly.points[i]);
    }
    EXPECT_FLOAT_EQ(minZ, -1.0f);
    EXPECT_LT(maxZ, 0.99f);
}

TEST(Subdivision, SharpCornersStayPut) {
    SubdivisionTags tags;
    tags.cornerIndices = {0, 1, 2, 3, 4, 5, 6, 7};
    tags.cornerSharpnesses.assign(8, 10.0f);
    const MeshInput m = refined(cube(), SubdivisionScheme::CatmullClark, 2, tags);
    EXPECT_TRUE(hasAllCubeCorners(m));
    expectOutwardNormals(m);
}

TEST(Subdivision, HolesRemoveTheirRefinedFaces) {
    SubdivisionTags tags;
    tags.holeIndices = {0};
    const MeshInput one = refined(cube(), SubdivisionScheme::CatmullClark, 1, tags);
    EXPECT_EQ(one.faceVertexCounts.size(), 20u);
    EXPECT_EQ(one.points.size() / 3, 26u);  // points stay: the hole's vertices shape its neighbours
    // Face 0 is the bottom: its face point, (0, 0, -1) at level 1, belongs to no remaining face.
    for (size_t i : usedPoints(one)) EXPECT_GT(length(minus(pointAt(one.points, i), {0, 0, -1})), 1e-3f) << i;
    EXPECT_EQ(refined(cube(), SubdivisionScheme::CatmullClark, 2, tags).faceVertexCounts.size(), 96u - 16u);
}

TEST(Subdivision, LoopRefinesTrianglesIntoTriangles) {
    for (int level = 1; level <= 3; ++level) {
        const MeshInput m = refined(tetrahedron(), SubdivisionScheme::Loop, level);
        EXPECT_EQ(m.faceVertexCounts, std::vector<int32_t>(size_t(4) << (2 * level), 3)) << level;
        expectOutwardNormals(m);
    }
}

TEST(Subdivision, BilinearKeepsPointsOnTheOriginalFaces) {
    const MeshInput m = refined(cube(), SubdivisionScheme::Bilinear, 2);
    EXPECT_EQ(m.faceVertexCounts, std::vector<int32_t>(96, 4));
    for (size_t i = 0; i < m.points.size() / 3; ++i) {
        const V3 p = pointAt(m.points, i);
        EXPECT_FLOAT_EQ(std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}), 1.0f) << i;
    }
    expectOutwardNormals(m);
}

TEST(Subdivision, InterpolateBoundaryShapesTheOpenBoundary) {
    SubdivisionTags tags;
    const MeshInput edgeAndCorner = refined(quadGrid(), SubdivisionScheme::CatmullClark, 1, tags);
    EXPECT_EQ(edgeAndCorner.faceVertexCounts.size(), 36u);
    EXPECT_TRUE(hasPoint(edgeAndCorner, {0, 0, 0}));  // the grid's corner is kept sharp

    tags.interpolateBoundary = "edgeOnly";
    const MeshInput edgeOnly = refined(quadGrid(), SubdivisionScheme::CatmullClark, 1, tags);
    EXPECT_EQ(edgeOnly.faceVertexCounts.size(), 36u);
    EXPECT_FALSE(hasPoint(edgeOnly, {0, 0, 0}));  // rounded along the boundary curve
    EXPECT_TRUE(hasPoint(edgeOnly, {0.125f, 0.125f, 0}));  // (1/8)(a + b) + (3/4)v

    // none: the faces along the boundary only support the surface, leaving the centre face's 4.
    tags.interpolateBoundary = "none";
    const MeshInput none = refined(quadGrid(), SubdivisionScheme::CatmullClark, 1, tags);
    EXPECT_EQ(none.faceVertexCounts.size(), 4u);
}

TEST(Subdivision, DisplayColorFollowsItsInterpolation) {
    MeshInput m = cube();
    m.displayColor = MeshPrimvar{{0.1f, 0.2f, 0.3f}, OBSCURA_INTERPOLATION_CONSTANT};
    EXPECT_EQ(refined(m, SubdivisionScheme::CatmullClark, 2).displayColor->values, m.displayColor->values);

    std::vector<float> perFace;
    for (int f = 0; f < 6; ++f) perFace.insert(perFace.end(), {float(f), 0.5f, 0.25f});
    m.displayColor = MeshPrimvar{perFace, OBSCURA_INTERPOLATION_UNIFORM};
    const MeshInput uniform = refined(m, SubdivisionScheme::CatmullClark, 2);
    ASSERT_EQ(uniform.displayColor->values.size(), 3 * uniform.faceVertexCounts.size());
    for (int f = 0; f < 6; ++f)
        EXPECT_EQ(std::count(uniform.displayColor->values.begin(), uniform.displayColor->values.end(), float(f)), 16) << f;

    // Face-varying with one colour per face: every refined corner takes its face's colour.
    std::vector<float> perCorner;
    for (int f = 0; f < 6; ++f)
        for (int k = 0; k < 4; ++k) perCorner.insert(perCorner.end(), {float(f), 0.5f, 0.25f});
    m.displayColor = MeshPrimvar{perCorner, OBSCURA_INTERPOLATION_FACE_VARYING};
    const MeshInput faceVarying = refined(m, SubdivisionScheme::CatmullClark, 2);
    EXPECT_EQ(faceVarying.displayColor->interpolation, OBSCURA_INTERPOLATION_FACE_VARYING);
    ASSERT_EQ(faceVarying.displayColor->values.size(), 3 * faceVarying.faceVertexIndices.size());
    size_t corner = 0;
    for (size_t face = 0; face < faceVarying.faceVertexCounts.size(); ++face)
        for (int32_t k = 0; k < faceVarying.faceVertexCounts[face]; ++k, ++corner)
            EXPECT_NEAR(faceVarying.displayColor->values[3 * corner], uniform.displayColor->values[3 * face], 1e-6f);

    // Vertex colours refine like the points: red = x maps onto the refined x.
    std::vector<float> perVertex;
    for (size_t i = 0; i < 8; ++i) perVertex.insert(perVertex.end(), {m.points[3 * i], 0.0f, 0.0f});
    m.displayColor = MeshPrimvar{perVertex, OBSCURA_INTERPOLATION_VERTEX};
    const MeshInput vertex = refined(m, SubdivisionScheme::CatmullClark, 2);
    ASSERT_EQ(vertex.displayColor->values.size(), vertex.points.size());
    for (size_t i = 0; i < vertex.points.size(); i += 3) EXPECT_NEAR(vertex.displayColor->values[i], vertex.points[i], 1e-6f);

    m.displayColor = MeshPrimvar{perVertex, OBSCURA_INTERPOLATION_UNIFORM};  // 8 values for 6 faces
    EXPECT_FALSE(refined(m, SubdivisionScheme::CatmullClark, 1).displayColor.has_value());
}

TEST(Subdivision, RefinedMeshBuildsIntoTrianglesWithoutWarnings) {
    MeshInput m = leftHandedCube();
    m.displayColor = MeshPrimvar{std::vector<float>(72, 0.5f), OBSCURA_INTERPOLATION_FACE_VARYING};
    SubdivisionTags tags;
    tags.holeIndices = {2};
    const auto built = buildMeshGeometry(refined(m, SubdivisionScheme::CatmullClark, 2, tags));
    ASSERT_TRUE(std::holds_alternative<MeshGeometry>(built));
    EXPECT_TRUE(std::get<MeshGeometry>(built).warnings.empty());
    EXPECT_EQ(std::get<MeshGeometry>(built).indices.size(), 3u * 2u * 80u);
}

TEST(Subdivision, CacheRebuildsTopologyOnlyWhenItChanges) {
    SubdivisionCache cache;
    MeshInput m = cube();
    const auto first = std::get<MeshInput>(cache.refine(m, SubdivisionScheme::CatmullClark, {}, 2));
    for (float& value : m.points) value *= 2.0f;  // animated points, same topology
    const auto second = std::get<MeshInput>(cache.refine(m, SubdivisionScheme::CatmullClark, {}, 2));
    EXPECT_EQ(cache.topologyBuilds(), 1u);
    ASSERT_EQ(second.points.size(), first.points.size());
    for (size_t i = 0; i < first.points.size(); ++i) EXPECT_NEAR(second.points[i], 2.0f * first.points[i], 1e-5f);

    SubdivisionTags hole;
    hole.holeIndices = {0};
    EXPECT_EQ(std::get<MeshInput>(cache.refine(m, SubdivisionScheme::CatmullClark, hole, 2)).faceVertexCounts.size(), 80u);
    EXPECT_EQ(cache.topologyBuilds(), 2u);
    cache.refine(m, SubdivisionScheme::CatmullClark, hole, 1);
    EXPECT_EQ(cache.topologyBuilds(), 3u);
    cache.refine(leftHandedCube(), SubdivisionScheme::CatmullClark, hole, 1);
    EXPECT_EQ(cache.topologyBuilds(), 4u);
    cache.refine(leftHandedCube(), SubdivisionScheme::CatmullClark, hole, 1);
    EXPECT_EQ(cache.topologyBuilds(), 4u);
    // A released refiner is built again by the next refinement, which gives the same mesh.
    const auto kept = std::get<MeshInput>(cache.refine(m, SubdivisionScheme::CatmullClark, {}, 2));
    cache.release();
    const auto rebuilt = std::get<MeshInput>(cache.refine(m, SubdivisionScheme::CatmullClark, {}, 2));
    EXPECT_EQ(cache.topologyBuilds(), 6u);
    EXPECT_EQ(rebuilt.points, kept.points);
    EXPECT_EQ(rebuilt.faceVertexIndices, kept.faceVertexIndices);
}

TEST(Subdivision, RejectsBadTopologyAndTags) {
    auto error = [](const MeshInput& mesh, const SubdivisionTags& tags = {},
                    SubdivisionScheme scheme = SubdivisionScheme::CatmullClark) -> std::string {
        auto result = refineMesh(mesh, scheme, tags, 1);
        return std::holds_alternative<std::string>(result) ? std::get<std::string>(result) : "";
    };
    MeshInput m = cube();
    m.faceVertexCounts[5] = 2;
    EXPECT_NE(error(m).find("faceVertexCounts[5]"), std::string::npos);
    m = cube();
    m.faceVertexCounts[5] = 5;
    EXPECT_NE(error(m).find("sum to 25"), std::string::npos);
    m = cube();
    m.faceVertexIndices[3] = 8;
    EXPECT_NE(error(m).find("outside"), std::string::npos);
    m.faceVertexIndices[3] = -1;
    EXPECT_NE(error(m).find("outside"), std::string::npos);
    EXPECT_NE(error(cube(), {}, SubdivisionScheme::Loop).find("triangles"), std::string::npos);

    SubdivisionTags tags;
    tags.interpolateBoundary = "sharp";
    EXPECT_NE(error(cube(), tags).find("interpolateBoundary"), std::string::npos);
    tags = {};
    tags.faceVaryingLinearInterpolation = "edgeAndCorner";
    EXPECT_NE(error(cube(), tags).find("faceVaryingLinearInterpolation"), std::string::npos);
    tags = creasedEdges(10.0f);
    tags.creaseSharpnesses.resize(5);
    EXPECT_NE(error(cube(), tags).find("creaseSharpnesses"), std::string::npos);
    tags = creasedEdges(10.0f);
    tags.creaseLengths[0] = 3;
    EXPECT_NE(error(cube(), tags).find("creaseLengths"), std::string::npos);
    tags = creasedEdges(10.0f);
    tags.creaseLengths[0] = 1;
    EXPECT_NE(error(cube(), tags).find("creaseLengths[0]"), std::string::npos);
    tags = creasedEdges(10.0f);
    tags.creaseIndices[0] = 99;
    EXPECT_NE(error(cube(), tags).find("creaseIndices[0]"), std::string::npos);
    tags = creasedEdges(-1.0f);
    EXPECT_NE(error(cube(), tags).find("creaseSharpnesses[0]"), std::string::npos);
    tags = {};
    tags.cornerIndices = {0, 1};
    tags.cornerSharpnesses = {10.0f};
    EXPECT_NE(error(cube(), tags).find("cornerSharpnesses"), std::string::npos);
    tags.cornerIndices = {8};
    EXPECT_NE(error(cube(), tags).find("cornerIndices[0]"), std::string::npos);
    tags = {};
    tags.holeIndices = {6};
    EXPECT_NE(error(cube(), tags).find("holeIndices[0]"), std::string::npos);
}

TEST(Subdivision, NonManifoldEdgesAreRefinedAsOpenSubdivSpecifies) {
    // Three quads sharing the edge 0-1: OpenSubdiv accepts non-manifold topology (its edges are
    // made sharp) and USD's topology validation does not reject it either.
    MeshInput m;
    m.points = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, -1, 0, 0, -1, 0, 1, 0, 1, 0, 0, 1};
    m.faceVertexCounts = {4, 4, 4};
    m.faceVertexIndices = {0, 1, 2, 3, 1, 0, 5, 4, 0, 1, 6, 7};
    const MeshInput out = refined(m, SubdivisionScheme::CatmullClark, 1);
    EXPECT_EQ(out.faceVertexCounts, std::vector<int32_t>(12, 4));
    for (float value : out.points) EXPECT_TRUE(std::isfinite(value));
}

TEST(Subdivision, LevelsOutsideTheRangeAreRejectedOrIgnored) {
    EXPECT_NE(std::get<std::string>(refineMesh(cube(), SubdivisionScheme::CatmullClark, {}, kMaxRefineLevel + 1)).find("level 7"),
              std::string::npos);
    for (int level : {0, -1}) {
        const MeshInput same = refined(cube(), SubdivisionScheme::CatmullClark, level);
        EXPECT_EQ(same.points, cube().points);
        EXPECT_EQ(same.faceVertexIndices, cube().faceVertexIndices);
    }
    EXPECT_EQ(refined(cube(), SubdivisionScheme::None, 2).faceVertexCounts, cube().faceVertexCounts);
    EXPECT_EQ(refined(cube(), SubdivisionScheme::CatmullClark, kMaxRefineLevel).faceVertexCounts.size(), 6u << 12);
}

// Refined faces keep their control face's group: every refined face of cube face f is in group f.
TEST(Subdivision, RefinedFacesKeepTheirControlFacesGroup) {
    MeshInput m = cube();
    m.faceGroups = {0, 1, 2, 3, 4, 5};
    const MeshInput out = refined(m, SubdivisionScheme::CatmullClark, 2);
    ASSERT_EQ(out.faceGroups.size(), out.faceVertexCounts.size());
    for (uint32_t group = 0; group < 6; ++group)
        EXPECT_EQ(std::count(out.faceGroups.begin(), out.faceGroups.end(), group), 16) << "group " << group;
    // Each refined face lies on its control face's side of the cube: the side's axis is extreme
    // at its points' centroid.
    const std::array<std::pair<int, float>, 6> sides{{{2, -1}, {2, 1}, {1, -1}, {1, 1}, {0, -1}, {0, 1}}};
    size_t base = 0;
    for (size_t face = 0; face < out.faceVertexCounts.size(); ++face) {
        V3 centroid{0, 0, 0};
        for (int32_t k = 0; k < out.faceVertexCounts[face]; ++k) {
            const V3 p = pointAt(out.points, size_t(out.faceVertexIndices[base + size_t(k)]));
            for (size_t c = 0; c < 3; ++c) centroid[c] += p[c] / float(out.faceVertexCounts[face]);
        }
        base += size_t(out.faceVertexCounts[face]);
        const auto [axis, sign] = sides[out.faceGroups[face]];
        for (size_t c = 0; c < 3; ++c)
            if (int(c) != axis) EXPECT_LT(std::fabs(centroid[c]), sign * centroid[size_t(axis)]) << "face " << face;
    }
}

}  // namespace
}  // namespace obscura::delegate
