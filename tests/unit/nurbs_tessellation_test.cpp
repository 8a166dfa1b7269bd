// NURBS patches' polygons against their definition: points on analytic surfaces that rational
// patches represent exactly (a cylinder, a sphere), agreement with the textbook recursive basis on
// a non-uniform knot vector, exact normals and their orientation, the chord bound the step count
// is chosen for, primvar interpolation, and bad data named.
#include "delegate/nurbs_tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace obscura::delegate {
namespace {

using V3 = std::array<double, 3>;

V3 at(const std::vector<float>& xyz, size_t i) { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

const double kHalfRoot2 = std::sqrt(0.5);

// The rational quadratic full circle (The NURBS Book, ex. 7.2): 9 points on the unit square,
// weights 1 and sqrt(2)/2, knots doubled at quarters. Counter-clockwise from +X.
struct Circle {
    std::vector<std::array<double, 2>> points{{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    std::vector<double> weights{1, kHalfRoot2, 1, kHalfRoot2, 1, kHalfRoot2, 1, kHalfRoot2, 1};
    NurbsDirection direction{9, 3, {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4}, {0, 0}};
};

// A cylinder of radius 1 from z = 0 to z = 2: the circle along u, a line along v.
NurbsPatchInput cylinder() {
    const Circle circle;
    NurbsPatchInput patch;
    patch.u = circle.direction;
    patch.v = {2, 2, {0, 0, 1, 1}, {0, 0}};
    for (double z : {0.0, 2.0})
        for (size_t i = 0; i < 9; ++i) {
            patch.points.insert(patch.points.end(), {float(circle.points[i][0]), float(circle.points[i][1]), float(z)});
            patch.pointWeights.push_back(float(circle.weights[i]));
        }
    return patch;
}

// A unit sphere: the circle along u swept along a half circle from the south pole (v).
NurbsPatchInput sphere() {
    const Circle circle;
    const std::vector<std::array<double, 2>> profile{{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}};  // (radial, z)
    const std::vector<double> profileWeights{1, kHalfRoot2, 1, kHalfRoot2, 1};
    NurbsPatchInput patch;
    patch.u = circle.direction;
    patch.v = {5, 3, {0, 0, 0, 1, 1, 2, 2, 2}, {0, 0}};
    for (size_t j = 0; j < 5; ++j)
        for (size_t i = 0; i < 9; ++i) {
            patch.points.insert(patch.points.end(), {float(circle.points[i][0] * profile[j][0]),
                                                     float(circle.points[i][1] * profile[j][0]), float(profile[j][1])});
            patch.pointWeights.push_back(float(circle.weights[i] * profileWeights[j]));
        }
    return patch;
}

TEST(NurbsTessellation, RationalCylinderAndSphereLieOnTheirSurfacesWithOutwardNormals) {
    for (const auto& [name, patch] : {std::pair{"cylinder", cylinder()}, std::pair{"sphere", sphere()}}) {
        ASSERT_EQ(nurbsPatchProblem(patch), "") << name;
        const NurbsTessellation t = tessellateNurbsPatch(patch, {4, 4});
        EXPECT_TRUE(t.warnings.empty()) << name;
        const bool isSphere = std::string(name) == "sphere";
        const size_t count = t.mesh.points.size() / 3;
        // 4 spans x 4 steps + 1 columns; rows: the cylinder 1 span, the sphere 2, 4 steps each.
        EXPECT_EQ(count, 17u * (isSphere ? 9u : 5u)) << name;
        for (size_t i = 0; i < count; ++i) {
            const V3 p = at(t.mesh.points, i), n = at(t.mesh.normals->values, i);
            const V3 radial = isSphere ? p : V3{p[0], p[1], 0.0};
            EXPECT_NEAR(std::sqrt(dot(radial, radial)), 1.0, 1e-6) << name << " point " << i;
            EXPECT_NEAR(dot(n, radial), 1.0, 1e-5) << name << " normal " << i;  // outward and unit (the poles too)
        }
    }
}

TEST(NurbsTessellation, LeftHandedTurnsTheNormalsAndTheWinding) {
    NurbsPatchInput patch = cylinder();
    patch.leftHanded = true;
    const NurbsTessellation t = tessellateNurbsPatch(patch, {2, 1});
    EXPECT_TRUE(t.mesh.leftHanded);
    const V3 p = at(t.mesh.points, 0), n = at(t.mesh.normals->values, 0);
    EXPECT_NEAR(dot(n, {p[0], p[1], 0.0}), -1.0, 1e-5);
}

// The textbook recursive definition (The NURBS Book, eq. 2.5), independent of the iterative one;
// the last span is closed at `end`, the valid range's end, where the others are half open.
double recursiveBasis(const std::vector<double>& U, int i, int p, double t, double end) {
    const double lo = U[size_t(i)], hi = U[size_t(i + 1)];
    if (p == 0) return (lo <= t && t < hi) || (t == end && hi == end && lo < hi) ? 1 : 0;
    double a = 0, b = 0;
    if (U[size_t(i + p)] > lo) a = (t - lo) / (U[size_t(i + p)] - lo) * recursiveBasis(U, i, p - 1, t, end);
    if (U[size_t(i + p + 1)] > hi) b = (U[size_t(i + p + 1)] - t) / (U[size_t(i + p + 1)] - hi) * recursiveBasis(U, i + 1, p - 1, t, end);
    return a + b;
}

TEST(NurbsTessellation, NonUniformCubicAgreesWithTheRecursiveBasisAndItsDefaultSt) {
    // 6 x 4 control points, cubic along u over non-uniform knots (a double knot inside), quadratic along v.
    NurbsPatchInput patch;
    patch.u = {6, 4, {0, 0, 0, 0, 0.3, 0.3, 1.5, 1.5, 1.5, 1.5}, {0, 0}};
    patch.v = {4, 3, {-1, -1, -1, 0.25, 2, 2, 2}, {0, 0}};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 6; ++i)
            patch.points.insert(patch.points.end(), {float(i), float(j), float(std::sin(i * 1.3 + j * 0.7))});
    ASSERT_EQ(nurbsPatchProblem(patch), "");
    const int steps = 3;
    const NurbsTessellation t = tessellateNurbsPatch(patch, {steps, steps});
    // Sample parameters: each drawn span's steps, boundaries shared.
    auto params = [&](const NurbsDirection& d) {
        std::vector<double> at;
        for (int s = d.order - 1; s < d.vertexCount; ++s) {
            const double lo = d.knots[size_t(s)], hi = d.knots[size_t(s + 1)];
            if (!(hi > lo)) continue;
            for (int k = at.empty() ? 0 : 1; k <= steps; ++k) at.push_back(lo + (hi - lo) * k / steps);
        }
        return at;
    };
    const std::vector<double> us = params(patch.u), vs = params(patch.v);
    ASSERT_EQ(t.mesh.points.size(), us.size() * vs.size() * 3);
    for (size_t j = 0; j < vs.size(); ++j)
        for (size_t i = 0; i < us.size(); ++i) {
            V3 expected{0, 0, 0};
            for (int b = 0; b < 4; ++b)
                for (int a = 0; a < 6; ++a) {
                    const double w = recursiveBasis(patch.u.knots, a, 3, us[i], 1.5) * recursiveBasis(patch.v.knots, b, 2, vs[j], 2.0);
                    for (size_t k = 0; k < 3; ++k) expected[k] += w * patch.points[size_t(b * 6 + a) * 3 + k];
                }
            const size_t vertex = j * us.size() + i;
            const V3 p = at(t.mesh.points, vertex);
            for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(p[k], expected[k], 2e-5) << "u " << us[i] << " v " << vs[j];
            // st: (u, v) normalised over the range.
            EXPECT_NEAR(t.mesh.st->values[2 * vertex], us[i] / 1.5, 1e-6);
            EXPECT_NEAR(t.mesh.st->values[2 * vertex + 1], (vs[j] + 1) / 3, 1e-6);
        }
    // A drawn range draws only its part.
    patch.u.range = {0.3, 1.5};
    const NurbsTessellation part = tessellateNurbsPatch(patch, {steps, steps});
    EXPECT_EQ(part.mesh.points.size() / 3, size_t(steps + 1) * vs.size());
    EXPECT_NEAR(part.mesh.points[0], t.mesh.points[3 * size_t(steps)], 1e-6);  // starts where span 2 did
}

// The surface between the polygon's vertices stays within bend / (8 n^2) of its chords: checked
// at the middle of every u edge of the sphere, for the steps a quarter-pixel bound asks for.
TEST(NurbsTessellation, StepsFromTheBendKeepChordsWithinTheirBound) {
    const NurbsPatchInput patch = sphere();
    const std::array<double, 2> bend = nurbsBendMagnitude(patch);
    EXPECT_GT(bend[0], 0.0);
    EXPECT_GT(bend[1], 0.0);
    for (double pixelsPerUnit : {50.0, 400.0, 3000.0}) {
        const double maxError = 0.25 / pixelsPerUnit;
        const int steps = int(std::ceil(std::sqrt(bend[0] / (8.0 * maxError))));
        const NurbsTessellation t = tessellateNurbsPatch(patch, {steps, 1});
        double worst = 0.0;
        for (size_t f = 0; f < t.mesh.faceVertexCounts.size(); ++f) {
            const V3 a = at(t.mesh.points, size_t(t.mesh.faceVertexIndices[4 * f]));
            const V3 b = at(t.mesh.points, size_t(t.mesh.faceVertexIndices[4 * f + 1]));
            const V3 mid{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
            const double ring = std::sqrt(1.0 - a[2] * a[2]);  // the radius of the circle the edge spans
            worst = std::max(worst, ring - std::hypot(mid[0], mid[1]));
        }
        EXPECT_LE(worst, maxError) << pixelsPerUnit << " px per unit, " << steps << " steps";
        EXPECT_GT(worst, maxError / 16) << "steps far finer than needed: the bend is overestimated";
    }
}

TEST(NurbsTessellation, PrimvarsFollowTheirInterpolation) {
    // Bilinear, 3 x 2 points: 2 spans along u, 1 along v.
    NurbsPatchInput patch;
    patch.u = {3, 2, {0, 0, 1, 2, 2}, {0, 0}};
    patch.v = {2, 2, {0, 0, 1, 1}, {0, 0}};
    patch.points = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0};
    // uniform: one per span; varying: one per span corner (3 x 2); vertex: through the basis.
    patch.displayColor = MeshPrimvar{{1, 0, 0, 0, 1, 0}, OBSCURA_INTERPOLATION_UNIFORM, 3};
    patch.displayOpacity = MeshPrimvar{{0, 0.5, 1, 0, 0.5, 1}, OBSCURA_INTERPOLATION_VARYING, 1};
    patch.st = MeshPrimvar{{0, 0, 2, 0, 4, 0, 0, 1, 2, 1, 4, 1}, OBSCURA_INTERPOLATION_VERTEX, 2};
    const NurbsTessellation t = tessellateNurbsPatch(patch, {2, 1});
    ASSERT_TRUE(t.warnings.empty()) << t.warnings.front();
    ASSERT_EQ(t.mesh.faceVertexCounts.size(), 4u);
    EXPECT_EQ(t.mesh.displayColor->interpolation, OBSCURA_INTERPOLATION_UNIFORM);
    EXPECT_EQ(t.mesh.displayColor->values, (std::vector<float>{1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0}));
    // Vertices along u at 0, 0.5, 1, 1.5, 2 (5 per row).
    EXPECT_EQ(t.mesh.displayOpacity->values, (std::vector<float>{0, 0.25f, 0.5f, 0.75f, 1, 0, 0.25f, 0.5f, 0.75f, 1}));
    for (size_t i = 0; i < 5; ++i) EXPECT_FLOAT_EQ(t.mesh.st->values[2 * i], float(i));
    // A count no interpolation allows: dropped with a warning naming it.
    patch.displayColor = MeshPrimvar{{1, 0, 0, 0, 1, 0, 0, 0, 1}, OBSCURA_INTERPOLATION_UNIFORM, 3};
    const NurbsTessellation dropped = tessellateNurbsPatch(patch, {1, 1});
    ASSERT_EQ(dropped.warnings.size(), 1u);
    EXPECT_NE(dropped.warnings[0].find("primvars:displayColor has 3 values but uniform interpolation on this patch needs 2"),
              std::string::npos)
        << dropped.warnings[0];
    EXPECT_FALSE(dropped.mesh.displayColor.has_value());
}

TEST(NurbsTessellation, BadDataIsNamed) {
    const std::vector<std::pair<std::function<void(NurbsPatchInput&)>, std::string>> cases = {
        {[](NurbsPatchInput& p) { p.u.knots.pop_back(); }, "uKnots has 11 values but uVertexCount + uOrder is 12"},
        {[](NurbsPatchInput& p) { p.v.knots = {0, 1, 0, 1}; }, "vKnots decrease at [2]"},
        {[](NurbsPatchInput& p) { p.v.order = 17; }, "vOrder is 17; it must be 2 to 16"},
        {[](NurbsPatchInput& p) { p.u.vertexCount = 2; }, "uVertexCount is 2; it must be at least uOrder (3)"},
        {[](NurbsPatchInput& p) { p.pointWeights[4] = 0; }, "pointWeights[4] is 0"},
        {[](NurbsPatchInput& p) { p.pointWeights.pop_back(); }, "pointWeights has 17 values but there are 18 points"},
        {[](NurbsPatchInput& p) { p.points.resize(p.points.size() - 3); }, "points has 17 values but uVertexCount x vVertexCount is 18"},
        {[](NurbsPatchInput& p) { p.u.range = {1, 5}; }, "uRange (1.000000, 5.000000) is not an increasing interval"},
        {[](NurbsPatchInput& p) { p.v.knots = {0, 0, 0, 0}; }, "vKnots give an empty parameter range"},
    };
    for (const auto& [breakIt, expected] : cases) {
        NurbsPatchInput patch = cylinder();
        breakIt(patch);
        const std::string problem = nurbsPatchProblem(patch);
        EXPECT_NE(problem.find(expected), std::string::npos) << "got: " << problem;
    }
}

}  // namespace
}  // namespace obscura::delegate
