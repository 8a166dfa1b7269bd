// Curves and points against their definitions (UsdGeomBasisCurves, UsdGeomPoints): segment
// counts per basis and wrap, the bases' values and derivatives at their knots (Bezier through its
// end points with 3 (P1 - P0) slopes, B-spline at (P0 + 4 P1 + P2) / 6, Catmull-Rom through its
// points with (P2 - P0) / 2 slopes, pinned curves through their ends), partition of unity,
// triangle counts equal to what is made, tubes at their radius with outward faces, spheres at
// theirs, and bad data named.
#include "delegate/curve_tessellation.h"
#include "renderer/matrix.h"
#include "delegate/prims/view_dependent_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

namespace obscura::delegate {
namespace {

using V3 = Vec3d;

V3 at(const std::vector<float>& xyz, size_t i) { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }
V3 positionOf(const passes::Vertex& v) { return {v.position[0], v.position[1], v.position[2]}; }
V3 normalOf(const passes::Vertex& v) { return {v.normal[0], v.normal[1], v.normal[2]}; }

// The curve's point and derivative at (segment, t) from its weights.
std::pair<V3, V3> evaluate(const std::vector<float>& points, CurveBasis basis, CurveWrap wrap, int segment, double t) {
    const int n = int(points.size() / 3);
    CurveWeights w = curveWeights(basis, wrap, n, segment, t);
    V3 p{0, 0, 0}, d{0, 0, 0};
    for (int k = 0; k < w.count; ++k) {
        p = add(p, scale(at(points, size_t(w.index[size_t(k)])), w.weight[size_t(k)]));
        d = add(d, scale(at(points, size_t(w.index[size_t(k)])), w.derivative[size_t(k)]));
    }
    return {p, d};
}

void expectNear(V3 a, V3 b, const char* what) {
    for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-9) << what << " component " << k;
}

// Six control points on a bent zig-zag (no three collinear).
const std::vector<float> kSix{0, 0, 0, 1, 2, 0, 2, -1, 1, 3, 1, 2, 4, 0, 1, 5, 2, 0};

TEST(CurveTessellation, SegmentCountsFollowTheBasisAndWrap) {
    EXPECT_EQ(curveSegmentCount(CurveBasis::Linear, CurveWrap::Nonperiodic, 5), 4);
    EXPECT_EQ(curveSegmentCount(CurveBasis::Linear, CurveWrap::Periodic, 5), 5);
    EXPECT_EQ(curveSegmentCount(CurveBasis::Linear, CurveWrap::Nonperiodic, 1), -1);
    EXPECT_EQ(curveSegmentCount(CurveBasis::Bezier, CurveWrap::Nonperiodic, 7), 2);
    EXPECT_EQ(curveSegmentCount(CurveBasis::Bezier, CurveWrap::Nonperiodic, 6), -1);
    EXPECT_EQ(curveSegmentCount(CurveBasis::Bezier, CurveWrap::Periodic, 6), 2);
    EXPECT_EQ(curveSegmentCount(CurveBasis::Bezier, CurveWrap::Pinned, 4), 1);
    for (CurveBasis basis : {CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        EXPECT_EQ(curveSegmentCount(basis, CurveWrap::Nonperiodic, 6), 3);
        EXPECT_EQ(curveSegmentCount(basis, CurveWrap::Periodic, 6), 6);
        EXPECT_EQ(curveSegmentCount(basis, CurveWrap::Pinned, 6), 5);
        EXPECT_EQ(curveSegmentCount(basis, CurveWrap::Nonperiodic, 3), -1);
    }
}

TEST(CurveTessellation, WeightsArePartitionsOfUnity) {
    for (CurveBasis basis : {CurveBasis::Linear, CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom})
        for (CurveWrap wrap : {CurveWrap::Nonperiodic, CurveWrap::Periodic, CurveWrap::Pinned}) {
            const int n = basis == CurveBasis::Bezier ? (wrap == CurveWrap::Periodic ? 6 : 7) : 6;
            for (int segment = 0; segment < curveSegmentCount(basis, wrap, n); ++segment)
                for (double t : {0.0, 0.3, 1.0}) {
                    CurveWeights w = curveWeights(basis, wrap, n, segment, t);
                    double sum = 0, slope = 0;
                    for (int k = 0; k < w.count; ++k) {
                        sum += w.weight[size_t(k)];
                        slope += w.derivative[size_t(k)];
                        EXPECT_GE(w.index[size_t(k)], 0);
                        EXPECT_LT(w.index[size_t(k)], n);
                    }
                    EXPECT_NEAR(sum, 1.0, 1e-12);
                    EXPECT_NEAR(slope, 0.0, 1e-12);
                }
        }
}

TEST(CurveTessellation, BezierPassesItsEndPointsWithSlopesAlongTheHull) {
    std::vector<float> seven(kSix);
    seven.insert(seven.end(), {6, 1, 1});
    auto [start, startSlope] = evaluate(seven, CurveBasis::Bezier, CurveWrap::Nonperiodic, 0, 0.0);
    auto [knot, knotSlope] = evaluate(seven, CurveBasis::Bezier, CurveWrap::Nonperiodic, 0, 1.0);
    auto [next, nextSlope] = evaluate(seven, CurveBasis::Bezier, CurveWrap::Nonperiodic, 1, 0.0);
    expectNear(start, at(seven, 0), "start");
    expectNear(startSlope, scale(sub(at(seven, 1), at(seven, 0)), 3.0), "start slope");
    expectNear(knot, at(seven, 3), "shared end point");
    expectNear(next, at(seven, 3), "next segment's start");
    expectNear(knotSlope, scale(sub(at(seven, 3), at(seven, 2)), 3.0), "slope into the knot");
    expectNear(evaluate(seven, CurveBasis::Bezier, CurveWrap::Nonperiodic, 1, 1.0).first, at(seven, 6), "end");
}

TEST(CurveTessellation, BsplineKnotsAreTheWeightedMeanAndContinuous) {
    for (int segment = 0; segment < 3; ++segment) {
        auto [p, d] = evaluate(kSix, CurveBasis::Bspline, CurveWrap::Nonperiodic, segment, 0.0);
        V3 expected = scale(add(add(at(kSix, size_t(segment)), scale(at(kSix, size_t(segment) + 1), 4.0)),
                                at(kSix, size_t(segment) + 2)),
                            1.0 / 6.0);
        expectNear(p, expected, "knot");
        expectNear(d, scale(sub(at(kSix, size_t(segment) + 2), at(kSix, size_t(segment))), 0.5), "knot slope");
        if (segment > 0) {
            auto [q, e] = evaluate(kSix, CurveBasis::Bspline, CurveWrap::Nonperiodic, segment - 1, 1.0);
            expectNear(q, p, "position across the knot");
            expectNear(e, d, "slope across the knot");
        }
    }
}

TEST(CurveTessellation, CatmullRomInterpolatesItsPoints) {
    for (int segment = 0; segment < 3; ++segment) {
        auto [p, d] = evaluate(kSix, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, segment, 0.0);
        expectNear(p, at(kSix, size_t(segment) + 1), "through its point");
        expectNear(d, scale(sub(at(kSix, size_t(segment) + 2), at(kSix, size_t(segment))), 0.5), "slope");
        expectNear(evaluate(kSix, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, segment, 1.0).first,
                   at(kSix, size_t(segment) + 2), "segment end");
    }
}

TEST(CurveTessellation, PinnedCurvesStartAndEndAtTheirEndPoints) {
    for (CurveBasis basis : {CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        expectNear(evaluate(kSix, basis, CurveWrap::Pinned, 0, 0.0).first, at(kSix, 0), "pinned start");
        expectNear(evaluate(kSix, basis, CurveWrap::Pinned, 4, 1.0).first, at(kSix, 5), "pinned end");
    }
}

TEST(CurveTessellation, PeriodicCurvesClose) {
    for (CurveBasis basis : {CurveBasis::Linear, CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        const int segments = curveSegmentCount(basis, CurveWrap::Periodic, 6);
        auto [end, endSlope] = evaluate(kSix, basis, CurveWrap::Periodic, segments - 1, 1.0);
        auto [start, startSlope] = evaluate(kSix, basis, CurveWrap::Periodic, 0, 0.0);
        expectNear(end, start, "closed");
        if (basis != CurveBasis::Linear && basis != CurveBasis::Bezier) expectNear(endSlope, startSlope, "smoothly closed");
    }
}

// Two gently bent loops (seven points for a nonperiodic Bezier, six otherwise) around the z axis,
// one above the other, 0.2 wide.
CurvesInput twoCurves(CurveBasis basis, CurveWrap wrap) {
    CurvesInput c;
    c.basis = basis;
    c.wrap = wrap;
    const int n = basis == CurveBasis::Bezier && wrap != CurveWrap::Periodic ? 7 : 6;
    for (float z : {0.0f, 5.0f})
        for (int k = 0; k < n; ++k) {
            double a = 2.0 * 3.14159265358979 * k / n;
            c.points.insert(c.points.end(), {float(2 * std::cos(a)), float(2 * std::sin(a)), z + float(0.3 * std::sin(2 * a))});
        }
    c.curveVertexCounts = {n, n};
    c.widths = MeshPrimvar{{0.2f}, OBSCURA_INTERPOLATION_CONSTANT, 1};
    return c;
}

// Every triangle's corners wind counter-clockwise about their vertex normals.
void expectOutwardFaces(const MeshGeometry& g) {
    for (size_t i = 0; i < g.indices.size(); i += 3) {
        const passes::Vertex &a = g.vertices[g.indices[i]], &b = g.vertices[g.indices[i + 1]], &c = g.vertices[g.indices[i + 2]];
        V3 face = cross(sub(positionOf(b), positionOf(a)), sub(positionOf(c), positionOf(a)));
        if (length(face) < 1e-12) continue;
        for (const passes::Vertex* v : {&a, &b, &c}) EXPECT_GT(dot(face, normalOf(*v)), 0.0) << "triangle " << i / 3;
    }
}

TEST(CurveTessellation, TubesAndRibbonsMakeTheTrianglesCountedAndFaceOutwards) {
    for (CurveBasis basis : {CurveBasis::Linear, CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom})
        for (CurveWrap wrap : {CurveWrap::Nonperiodic, CurveWrap::Periodic, CurveWrap::Pinned})
            for (bool ribbon : {false, true}) {
                SCOPED_TRACE("basis " + std::to_string(int(basis)) + " wrap " + std::to_string(int(wrap)) + " ribbon " +
                             std::to_string(ribbon));
                CurvesInput c = twoCurves(basis, wrap);
                ASSERT_EQ(curvesProblem(c), "");
                if (ribbon) c.normals = MeshPrimvar{{0, 0, 1}, OBSCURA_INTERPOLATION_CONSTANT, 3};
                const CurveDetail detail{16, 4};
                MeshGeometry g = tessellateCurves(c, detail);
                EXPECT_TRUE(g.warnings.empty());
                EXPECT_EQ(g.indices.size() / 3, curveTriangleCount(c, detail));
                expectOutwardFaces(g);
            }
}

TEST(CurveTessellation, TubeRingsLieAtTheirRadiusAroundTheCurve) {
    CurvesInput c;
    c.basis = CurveBasis::Linear;
    c.points = {0, 0, 0, 0, 0, 4};
    c.curveVertexCounts = {2};
    c.widths = MeshPrimvar{{0.5f, 1.5f}, OBSCURA_INTERPOLATION_VERTEX, 1};
    MeshGeometry g = tessellateCurves(c, {8, 1});
    for (const passes::Vertex& v : g.vertices) {
        V3 p = positionOf(v);
        const double expected = 0.5 * (0.5 + (1.5 - 0.5) * p[2] / 4.0);
        const bool cap = std::fabs(normalOf(v)[2]) > 0.5;
        EXPECT_NEAR(std::hypot(p[0], p[1]), expected, 1e-6);
        if (!cap) EXPECT_NEAR(dot(normalOf(v), {p[0] / expected, p[1] / expected, 0}), 1.0, 1e-5);
    }
    // Linear curves take one step per segment whatever the detail asks for.
    EXPECT_EQ(tessellateCurves(c, {8, 16}).indices.size(), g.indices.size());
}

// Non-constant displayOpacity reaches the vertices as displayColor does: vertex opacity follows the
// curve's parameter, uniform opacity is one per curve; one of the wrong count is dropped with a
// warning and the curves stay opaque.
TEST(CurveTessellation, DisplayOpacityFollowsItsInterpolation) {
    CurvesInput c;
    c.basis = CurveBasis::Linear;
    c.points = {0, 0, 0, 0, 0, 4, 3, 0, 0, 3, 0, 4};  // along z at x = 0 and x = 3
    c.curveVertexCounts = {2, 2};
    c.displayOpacity = MeshPrimvar{{0.2f, 1.0f, 0.5f, 0.5f}, OBSCURA_INTERPOLATION_VERTEX, 1};
    MeshGeometry g = tessellateCurves(c, {8, 1});
    EXPECT_TRUE(g.warnings.empty());
    for (const passes::Vertex& v : g.vertices)
        EXPECT_NEAR(v.color[3], v.position[0] < 1.5f ? 0.2 + 0.8 * v.position[2] / 4.0 : 0.5, 1e-6);
    c.displayOpacity = MeshPrimvar{{0.25f, 0.75f}, OBSCURA_INTERPOLATION_UNIFORM, 1};
    for (const passes::Vertex& v : tessellateCurves(c, {8, 1}).vertices)
        EXPECT_EQ(v.color[3], v.position[0] < 1.5f ? 0.25f : 0.75f);
    c.displayOpacity = MeshPrimvar{{0.5f, 0.5f, 0.5f}, OBSCURA_INTERPOLATION_VERTEX, 1};
    MeshGeometry dropped = tessellateCurves(c, {8, 1});
    EXPECT_EQ(dropped.warnings, std::vector<std::string>{"primvars:displayOpacity has 3 elements but its interpolation "
                                                         "needs 4; ignored"});
    for (const passes::Vertex& v : dropped.vertices) EXPECT_EQ(v.color[3], 1.0f);
}

TEST(CurveTessellation, BadCurvesAreNamed) {
    CurvesInput c = twoCurves(CurveBasis::Bspline, CurveWrap::Nonperiodic);
    c.curveVertexCounts = {6, 5};
    EXPECT_NE(curvesProblem(c).find("sum to 11 but there are 12 points"), std::string::npos) << curvesProblem(c);
    c = twoCurves(CurveBasis::Bezier, CurveWrap::Nonperiodic);
    c.curveVertexCounts = {6, 8};
    EXPECT_NE(curvesProblem(c).find("curveVertexCounts[0] is 6"), std::string::npos) << curvesProblem(c);
    c = twoCurves(CurveBasis::Linear, CurveWrap::Nonperiodic);
    c.widths = MeshPrimvar{{0.1f, 0.2f, 0.3f}, OBSCURA_INTERPOLATION_VERTEX, 1};
    EXPECT_NE(curvesProblem(c).find("widths has 3 elements but its interpolation needs 12"), std::string::npos)
        << curvesProblem(c);
    c.widths = MeshPrimvar{{0.1f, -0.5f}, OBSCURA_INTERPOLATION_UNIFORM, 1};
    EXPECT_NE(curvesProblem(c).find("widths[1] is -0.5"), std::string::npos) << curvesProblem(c);
    // Varying: one per segment end (bspline: n - 3 segments, n - 2 ends on each curve).
    c = twoCurves(CurveBasis::Bspline, CurveWrap::Nonperiodic);
    EXPECT_EQ(curvePrimvarElementCount(c, OBSCURA_INTERPOLATION_VARYING), 8u);
    c.wrap = CurveWrap::Periodic;
    EXPECT_EQ(curvePrimvarElementCount(c, OBSCURA_INTERPOLATION_VARYING), 12u);
    // Normals of the wrong size only lose the ribbons: a warning, tubes drawn.
    c.normals = MeshPrimvar{{0, 0, 1, 0, 0, 1}, OBSCURA_INTERPOLATION_VERTEX, 3};
    MeshGeometry g = tessellateCurves(c, {8, 2});
    ASSERT_EQ(g.warnings.size(), 1u);
    EXPECT_NE(g.warnings[0].find("normals"), std::string::npos);
}

TEST(CurveTessellation, BendMagnitudeIsZeroForStraightCubics) {
    CurvesInput c;
    c.basis = CurveBasis::Bezier;
    c.points = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
    c.curveVertexCounts = {4};
    EXPECT_NEAR(curveBendMagnitude(c), 0.0, 1e-12);
    c.points = {0, 0, 0, 0, 1, 0, 1, 1, 0, 1, 0, 0};
    EXPECT_NEAR(curveBendMagnitude(c), std::sqrt(2.0), 1e-12);  // |Q0 - 2 Q1 + Q2| = |(1, -1, 0)|
}

TEST(PointTessellation, EachPointIsTheCubeBoundingItsSphereCarryingItsOffsetAndRadius) {
    PointsInput p;
    p.points = {0, 0, 0, 3, 1, -2};
    p.widths = MeshPrimvar{{1.0f, 0.5f}, OBSCURA_INTERPOLATION_VERTEX, 1};
    ASSERT_EQ(pointsProblem(p), "");
    MeshGeometry g = pointImpostorBoxes(p);
    ASSERT_EQ(g.vertices.size(), 16u);
    EXPECT_EQ(g.indices.size() / 3, pointTriangleCount(p));
    EXPECT_EQ(pointTriangleCount(p), 24u);
    for (size_t i = 0; i < g.vertices.size(); ++i) {
        const size_t point = i / 8;
        const double radius = point == 0 ? 0.5 : 0.25;
        const passes::Vertex& v = g.vertices[i];
        V3 offset = sub(positionOf(v), at(p.points, point));
        for (size_t k = 0; k < 3; ++k) {
            EXPECT_NEAR(std::abs(offset[k]), radius, 1e-6) << "a corner of the cube around the sphere";
            EXPECT_NEAR(v.tangent[k], offset[k], 1e-6) << "the corner's offset from its point";
        }
        EXPECT_FLOAT_EQ(v.tangent[3], float(radius));
    }
    for (size_t t = 0; t < g.indices.size(); t += 3)
        EXPECT_EQ(g.indices[t] / 8, g.indices[t + 2] / 8) << "a triangle joins corners of one point's cube";
    expectOutwardFaces(g);
    p.widths = MeshPrimvar{{1.0f}, OBSCURA_INTERPOLATION_VERTEX, 1};
    EXPECT_NE(pointsProblem(p).find("widths has 1 elements but its interpolation needs 2"), std::string::npos);
    p.widths = MeshPrimvar{{-1.0f}, OBSCURA_INTERPOLATION_CONSTANT, 1};
    EXPECT_NE(pointsProblem(p).find("widths[0] is -1"), std::string::npos);
}

TEST(TessellationCap, CoarsensToTheFinestLevelWithinTheCapOrRefuses) {
    auto quadrupling = [](int level) { return uint64_t(1000) << (2 * level); };  // 1000 x 4^level
    CappedLevel fits = capTessellation(5, 0, quadrupling, "/P");
    EXPECT_EQ(fits.level, 5);
    EXPECT_EQ(fits.warning, "");
    // 1000 x 4^7 is 16.4 million, over the 8 million cap; 1000 x 4^6 is 4.1 million, within it.
    CappedLevel capped = capTessellation(9, 0, quadrupling, "/P");
    EXPECT_EQ(capped.level, 6);
    EXPECT_NE(capped.warning.find("262144000 its size on screen asks for were cut to 4096000"), std::string::npos)
        << capped.warning;
    EXPECT_THROW(capTessellation(9, 7, quadrupling, "/P"), PrimDataError);
}

}  // namespace
}  // namespace obscura::delegate
