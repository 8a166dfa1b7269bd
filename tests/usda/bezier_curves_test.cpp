// NurbsCurves and HermiteCurves as cubic Bezier curves, against curves whose shape is known: a
// rational quadratic NURBS circle stays within the conversion's tolerance of its radius, a uniform
// cubic B-spline is reproduced to rounding as de Boor's algorithm evaluates it (widths with it), a
// polyline of order 2 stays straight, a Hermite curve is its Hermite polynomial, and bad data is
// refused naming the attribute.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "harness/usda/hermite_curves.h"
#include "harness/usda/nurbs_curves.h"
#include "usda_test_util.h"

namespace obscura::usda::test {
namespace {

using Vec3 = std::array<double, 3>;

// Point u in [0, 1] of Bezier segment `segment` of the first converted curve, from its control points.
Vec3 bezierAt(const std::vector<double>& controls, size_t segment, double u) {
    const double v = 1.0 - u;
    const double b[4] = {v * v * v, 3 * u * v * v, 3 * u * u * v, u * u * u};
    Vec3 p{0, 0, 0};
    for (size_t k = 0; k < 4; ++k)
        for (size_t c = 0; c < 3; ++c) p[c] += b[k] * controls[(3 * segment + k) * 3 + c];
    return p;
}

BezierCurves converted(const std::variant<BezierCurves, AttributeProblem>& result) {
    if (auto* problem = std::get_if<AttributeProblem>(&result)) {
        ADD_FAILURE() << problem->attribute << ": " << problem->message;
        return {};
    }
    return std::get<BezierCurves>(result);
}

// de Boor's algorithm (de Boor 1972; The NURBS Book, A3.1's pyramid) for a polynomial B-spline of
// degree p at t in span s: the reference the conversion is checked against.
std::vector<double> deBoor(const std::vector<double>& knots, const std::vector<double>& points, size_t components, size_t p,
                           size_t s, double t) {
    std::vector<std::vector<double>> d;
    for (size_t j = 0; j <= p; ++j)
        d.emplace_back(points.begin() + long((s - p + j) * components), points.begin() + long((s - p + j + 1) * components));
    for (size_t r = 1; r <= p; ++r)
        for (size_t j = p; j >= r; --j) {
            const size_t i = s - p + j;
            const double alpha = (t - knots[i]) / (knots[i + p + 1 - r] - knots[i]);
            for (size_t c = 0; c < components; ++c) d[j][c] = (1.0 - alpha) * d[j - 1][c] + alpha * d[j][c];
        }
    return d[p];
}

TEST(NurbsCurves, RationalQuadraticCircleStaysOnItsRadius) {
    const double w = std::sqrt(0.5);
    NurbsCurvesData circle;
    const std::vector<double> points = {1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0, -1, 0, 0, -1, -1, 0, 0, -1, 0, 1, -1, 0, 1, 0, 0};
    circle.curveVertexCounts = {9};
    circle.order = {3};
    circle.knots = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
    circle.pointWeights = {1, w, 1, w, 1, w, 1, w, 1};
    circle.pointCount = 9;
    const BezierCurves bezier = converted(nurbsToBezier(circle));
    ASSERT_EQ(bezier.curveVertexCounts.size(), 1u) << "one closed curve stays one Bezier curve";
    const size_t segments = size_t(bezier.curveVertexCounts[0] - 1) / 3;
    EXPECT_EQ(segments % 4, 0u) << "each quarter is cut into the same pieces";
    EXPECT_GT(segments, 4u) << "a rational quarter is no cubic";
    EXPECT_LE(segments, 4u * 16u) << "the tolerance is reached with few pieces";
    const std::vector<double> controls = bezier.positions.apply(points, 3);
    // The span's control points (a corner and its two neighbours) lie within sqrt(2) / 2 of their
    // centre: the conversion's bound on the distance from the circle.
    const double bound = kNurbsTolerance * std::sqrt(0.5);
    double worst = 0.0;
    for (size_t segment = 0; segment < segments; ++segment)
        for (int k = 0; k <= 64; ++k) {
            const Vec3 p = bezierAt(controls, segment, k / 64.0);
            worst = std::max(worst, std::abs(std::hypot(p[0], p[1]) - 1.0));
            EXPECT_EQ(p[2], 0.0);
        }
    EXPECT_LE(worst, bound);
    EXPECT_GT(worst, 0.0) << "a cubic is not a circle: the test measures something";
    // It starts and ends at (1, 0), through (0, 1) a quarter of the way.
    EXPECT_NEAR(controls[0], 1.0, 1e-12);
    EXPECT_NEAR(controls[controls.size() - 3], 1.0, 1e-12);
    const Vec3 quarter = bezierAt(controls, segments / 4 - 1, 1.0);
    EXPECT_NEAR(quarter[0], 0.0, 1e-12);
    EXPECT_NEAR(quarter[1], 1.0, 1e-12);
}

TEST(NurbsCurves, UniformCubicBsplineIsDeBoorsCurveExactly) {
    NurbsCurvesData spline;
    const std::vector<double> points = {0, 0, 0, 1, 2, 0, 2, -1, 1, 3, 3, -2, 5, 0, 1, 6, 2, 2};
    const std::vector<double> widths = {0.1, 0.4, 0.2, 0.6, 0.3, 0.5};
    spline.curveVertexCounts = {6};
    spline.order = {4};
    spline.knots = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    spline.pointCount = 6;
    const BezierCurves bezier = converted(nurbsToBezier(spline));
    // The valid range [knots[3], knots[6]] holds three spans: three segments, one per span.
    ASSERT_EQ(bezier.curveVertexCounts, std::vector<int>{10});
    const std::vector<double> controls = bezier.positions.apply(points, 3);
    const std::vector<double> widthControls = bezier.vertex.apply(widths, 1);
    for (size_t segment = 0; segment < 3; ++segment)
        for (int k = 0; k <= 16; ++k) {
            const double u = k / 16.0, t = 3.0 + double(segment) + u;
            const std::vector<double> expected = deBoor(spline.knots, points, 3, 3, 3 + segment, t);
            const Vec3 p = bezierAt(controls, segment, u);
            for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c], 1e-12) << "segment " << segment << " u " << u;
            const double v = 1.0 - u;
            const double* wc = &widthControls[3 * segment];
            const double width = v * v * v * wc[0] + 3 * u * v * v * wc[1] + 3 * u * u * v * wc[2] + u * u * u * wc[3];
            EXPECT_NEAR(width, deBoor(spline.knots, widths, 1, 3, 3 + segment, t)[0], 1e-12);
        }
    // Varying values: one per segment end of the authored curve (nVerts - order + 2), to the same ends.
    EXPECT_EQ(bezier.varying.inputCount, 4u);
    EXPECT_EQ(bezier.varying.apply({10, 20, 30, 40}, 1), (std::vector<double>{10, 20, 30, 40}));
}

TEST(NurbsCurves, RangesAndVaryingValuesFollowTheParameter) {
    NurbsCurvesData line;
    line.curveVertexCounts = {3};
    line.order = {2};
    line.knots = {0, 0, 1, 3, 3};
    line.ranges = {0.5, 2.0};
    line.pointCount = 3;
    const BezierCurves bezier = converted(nurbsToBezier(line));
    // Order 2: straight segments, exact. [0.5, 2] crosses the knot at 1: two segments.
    ASSERT_EQ(bezier.curveVertexCounts, std::vector<int>{7});
    const std::vector<double> controls = bezier.positions.apply({0, 0, 0, 2, 0, 0, 2, 4, 0}, 3);
    const std::vector<double> expected = {1, 0, 0, 4.0 / 3, 0, 0, 5.0 / 3, 0, 0, 2, 0, 0, 2, 2.0 / 3, 0, 2, 4.0 / 3, 0, 2, 2, 0};
    ASSERT_EQ(controls.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(controls[i], expected[i], 1e-12) << i;
    // Varying values at the knots 0, 1, 3, linear in the parameter between them.
    EXPECT_EQ(bezier.varying.apply({0, 10, 30}, 1), (std::vector<double>{5, 10, 20}));
}

TEST(NurbsCurves, AJumpAtAKnotOfFullMultiplicityStartsAnotherBezierCurve) {
    NurbsCurvesData two;
    two.curveVertexCounts = {4};
    two.order = {2};
    two.knots = {0, 0, 1, 1, 2, 2};
    two.pointCount = 4;
    const BezierCurves bezier = converted(nurbsToBezier(two));
    EXPECT_EQ(bezier.curveVertexCounts, (std::vector<int>{4, 4}));
    EXPECT_EQ(bezier.sourceCurves, (std::vector<size_t>{0, 0}));
    Value uniform{"float", true, 1, {7.0}, {}, false};
    auto perCurve = convertCurvesPrimvar(bezier, uniform, "uniform", 1);
    ASSERT_TRUE(std::holds_alternative<Value>(perCurve));
    EXPECT_EQ(std::get<Value>(perCurve).numbers.vector(), (std::vector<double>{7, 7}));
}

TEST(NurbsCurves, BadDataNamesTheAttribute) {
    auto problemOf = [](NurbsCurvesData data) {
        auto result = nurbsToBezier(data);
        return std::holds_alternative<AttributeProblem>(result) ? std::get<AttributeProblem>(result) : AttributeProblem{};
    };
    NurbsCurvesData good;
    good.curveVertexCounts = {4};
    good.order = {4};
    good.knots = {0, 0, 0, 0, 1, 1, 1, 1};
    good.pointCount = 4;
    EXPECT_TRUE(std::holds_alternative<BezierCurves>(nurbsToBezier(good)));
    auto bad = good;
    bad.pointCount = 5;
    EXPECT_EQ(problemOf(bad).attribute, "curveVertexCounts");
    bad = good;
    bad.knots.pop_back();
    EXPECT_EQ(problemOf(bad).attribute, "knots");
    bad = good;
    bad.knots = {0, 0, 0, 2, 1, 1, 1, 1};
    EXPECT_EQ(problemOf(bad).attribute, "knots");
    EXPECT_NE(problemOf(bad).message.find("decrease at knots[4]"), std::string::npos) << problemOf(bad).message;
    for (int order : {1, 5}) {
        bad = good;
        bad.order = {order};
        bad.knots.resize(size_t(4 + order), 1.0);
        EXPECT_EQ(problemOf(bad).attribute, "order") << order;
    }
    bad = good;
    bad.pointWeights = {1, 1, 1};
    EXPECT_EQ(problemOf(bad).attribute, "pointWeights");
    bad.pointWeights = {1, 0, 1, 1};
    EXPECT_EQ(problemOf(bad).attribute, "pointWeights");
    bad = good;
    bad.ranges = {0.5, 2.0};
    EXPECT_EQ(problemOf(bad).attribute, "ranges");
}

TEST(NurbsCurves, AnyInputIsConvertedOrRefused) {
    // Random curves, half of them with a value spoiled (NaN, infinite, huge, negative): each
    // conversion either succeeds with counts that fit or names a problem, and never reads outside
    // its arrays (scripts/test.sh runs it under the sanitizers).
    std::mt19937 random(7);
    auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
    const double spoilers[] = {std::nan(""), INFINITY, -INFINITY, 1e300, -1.0, 0.0};
    for (int trial = 0; trial < 2000; ++trial) {
        NurbsCurvesData data;
        for (int curve = pick(0, 3); curve > 0; --curve) {
            const int n = pick(1, 7), order = pick(1, 6);
            data.curveVertexCounts.push_back(n);
            data.order.push_back(order);
            double knot = 0.0;
            for (int k = 0; k < n + order; ++k) data.knots.push_back(knot += pick(0, 2));
            data.pointCount += size_t(n);
            if (pick(0, 1)) data.ranges.insert(data.ranges.end(), {double(pick(0, 4)), double(pick(0, 12))});
        }
        if (pick(0, 1))
            for (size_t i = 0; i < data.pointCount; ++i) data.pointWeights.push_back(pick(1, 100) / 10.0);
        if (pick(0, 1) && !data.knots.empty()) data.knots[size_t(pick(0, int(data.knots.size()) - 1))] = spoilers[pick(0, 5)];
        if (pick(0, 3) == 0 && !data.pointWeights.empty()) data.pointWeights[0] = spoilers[pick(0, 5)];
        if (pick(0, 3) == 0) data.pointCount += size_t(pick(0, 2));
        auto result = nurbsToBezier(data);
        if (auto* bezier = std::get_if<BezierCurves>(&result)) {
            size_t controls = 0;
            for (int count : bezier->curveVertexCounts) {
                EXPECT_EQ((count - 1) % 3, 0);
                controls += size_t(count);
            }
            EXPECT_EQ(bezier->vertex.rows(), controls);
            for (size_t column : bezier->vertex.columns) EXPECT_LT(column, data.pointCount);
            for (size_t column : bezier->varying.columns) EXPECT_LT(column, bezier->varying.inputCount);
        } else {
            EXPECT_FALSE(std::get<AttributeProblem>(result).message.empty());
        }
    }
}

TEST(HermiteCurves, EachSegmentIsItsHermitePolynomial) {
    const std::vector<double> points = {0, 0, 0, 2, 1, 0, 3, -1, 1};
    const std::vector<double> tangents = {1, 3, 0, 2, 0, -1, 0, -4, 2};
    const BezierCurves bezier = converted(hermiteToBezier({3}, 3, 3));
    ASSERT_EQ(bezier.curveVertexCounts, std::vector<int>{7});
    std::vector<double> input = points;
    input.insert(input.end(), tangents.begin(), tangents.end());
    const std::vector<double> controls = bezier.positions.apply(input, 3);
    for (size_t segment = 0; segment < 2; ++segment)
        for (int k = 0; k <= 8; ++k) {
            const double u = k / 8.0, u2 = u * u, u3 = u2 * u;
            // The cubic Hermite basis h00, h10, h01, h11.
            const double h[4] = {2 * u3 - 3 * u2 + 1, u3 - 2 * u2 + u, -2 * u3 + 3 * u2, u3 - u2};
            const Vec3 p = bezierAt(controls, segment, u);
            for (size_t c = 0; c < 3; ++c) {
                const double expected = h[0] * points[3 * segment + c] + h[1] * tangents[3 * segment + c] +
                                        h[2] * points[3 * segment + 3 + c] + h[3] * tangents[3 * segment + 3 + c];
                EXPECT_NEAR(p[c], expected, 1e-12);
            }
        }
    // Vertex primvars run linearly along each segment.
    EXPECT_EQ(bezier.vertex.apply({0, 3, 6}, 1), (std::vector<double>{0, 1, 2, 3, 4, 5, 6}));
}

TEST(HermiteCurves, BadDataNamesTheAttribute) {
    auto attributeOf = [](const std::variant<BezierCurves, AttributeProblem>& result) {
        return std::holds_alternative<AttributeProblem>(result) ? std::get<AttributeProblem>(result).attribute : "";
    };
    EXPECT_EQ(attributeOf(hermiteToBezier({3}, 3, 2)), "tangents");
    EXPECT_EQ(attributeOf(hermiteToBezier({3}, 4, 4)), "curveVertexCounts");
    EXPECT_EQ(attributeOf(hermiteToBezier({1}, 1, 1)), "curveVertexCounts");
}

TEST(BezierCurves, PrimvarCountsMustFitTheirInterpolation) {
    const BezierCurves bezier = converted(hermiteToBezier({2, 2}, 4, 4));
    Value vertex{"float", true, 1, {1, 2, 3}, {}, false};
    auto result = convertCurvesPrimvar(bezier, vertex, "vertex", 1);
    ASSERT_TRUE(std::holds_alternative<std::string>(result));
    EXPECT_EQ(std::get<std::string>(result), "3 values but vertex interpolation needs 4");
    Value constant{"color3f", true, 3, {1, 0, 0}, {}, false};
    EXPECT_EQ(std::get<Value>(convertCurvesPrimvar(bezier, constant, "constant", 1)).numbers.vector(),
              (std::vector<double>{1, 0, 0}));
}

TEST(NurbsCurves, PrimAttributesAreRead) {
    auto stage = open(R"(#usda 1.0
def NurbsCurves "Curve"
{
    point3f[] points = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0)]
    int[] curveVertexCounts = [4]
    int[] order = [4]
    double[] knots = [0, 0, 0, 0, 1, 1, 1]
}
)");
    ASSERT_TRUE(stage);
    auto result = nurbsCurvesAsBezier(*stage->find("/Curve"), 0.0);
    ASSERT_TRUE(std::holds_alternative<AttributeProblem>(result));
    EXPECT_EQ(std::get<AttributeProblem>(result).attribute, "knots");
    EXPECT_EQ(std::get<AttributeProblem>(result).message, "knots has 7 values but the curves need 8 (vertex count + order each)");
}

}  // namespace
}  // namespace obscura::usda::test
