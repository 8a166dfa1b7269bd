// Trim curves against the regions they bound: a round hole cut from a flat patch leaves the
// square's area less the disc's, its cut edge lies on the circle, and the kept side follows the
// loops' orientation (an island, an outer boundary with a hole); the detail the tessellation
// takes resolves the loops; malformed trim data is named.
#include "delegate/nurbs_tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace obscura::delegate {
namespace {

const double kPi = 3.14159265358979323846;
const double kHalfRoot2 = std::sqrt(0.5);

// The unit square z = 0 as a bilinear patch whose (u, v) is its (x, y).
NurbsPatchInput square() {
    NurbsPatchInput patch;
    patch.u = {2, 2, {0, 0, 1, 1}, {0, 0}};
    patch.v = {2, 2, {0, 0, 1, 1}, {0, 0}};
    patch.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    return patch;
}

// A loop of one rational quadratic full circle (The NURBS Book, ex. 7.2) about (cu, cv) in the
// parameter space, counter-clockwise unless `clockwise`, its points homogeneous (u w, v w, w).
void addCircle(NurbsTrimCurves& trim, double cu, double cv, double r, bool clockwise) {
    const double p[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    trim.counts.push_back(1);
    trim.orders.push_back(3);
    trim.vertexCounts.push_back(9);
    for (double k : {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4}) trim.knots.push_back(k);
    trim.ranges.push_back({0, 4});
    for (int i = 0; i < 9; ++i) {
        const double w = i % 2 == 0 ? 1.0 : kHalfRoot2;
        const double y = clockwise ? -p[i][1] : p[i][1];
        trim.points.push_back({(cu + r * p[i][0]) * w, (cv + r * y) * w, w});
    }
}

// A counter-clockwise square loop [lo, hi]^2 of one linear curve.
void addSquare(NurbsTrimCurves& trim, double lo, double hi) {
    trim.counts.push_back(1);
    trim.orders.push_back(2);
    trim.vertexCounts.push_back(5);
    for (double k : {0, 0, 1, 2, 3, 4, 4}) trim.knots.push_back(k);
    trim.ranges.push_back({0, 4});
    for (auto [u, v] : std::vector<std::pair<double, double>>{{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}, {lo, lo}})
        trim.points.push_back({u, v, 1.0});
}

// The area of the tessellation's faces (the patch lies in z = 0).
double area(const MeshInput& mesh) {
    double sum = 0.0;
    size_t first = 0;
    for (int32_t n : mesh.faceVertexCounts) {
        for (int32_t k = 0; k < n; ++k) {
            const size_t a = size_t(mesh.faceVertexIndices[first + size_t(k)]);
            const size_t b = size_t(mesh.faceVertexIndices[first + size_t((k + 1) % n)]);
            sum += 0.5 * (double(mesh.points[3 * a]) * mesh.points[3 * b + 1] - double(mesh.points[3 * b]) * mesh.points[3 * a + 1]);
        }
        first += size_t(n);
    }
    return sum;
}

NurbsTessellation trimmed(const NurbsPatchInput& patch) {
    EXPECT_EQ(nurbsPatchProblem(patch), "");
    return tessellateNurbsPatch(patch, nurbsTrimSteps(patch));
}

// Within a cell the boundary runs straight between the points where the circle crosses the cell's
// edges: chords at most the cell's diagonal h sqrt 2 long, each within (2 h^2) / (8 r) of the
// circle, so the polygon (inscribed: the hole smaller than the disc, the island too) misses at most
// two thirds of that over the circumference: pi h^2 / 3 of area.
double polygonAreaBound(double h) { return kPi * h * h / 3.0; }

TEST(NurbsTrim, RoundHoleLeavesTheSquareLessTheDiscAndItsEdgeOnTheCircle) {
    const double r = 0.25;
    NurbsPatchInput patch = square();
    addCircle(patch.trimCurves, 0.5, 0.5, r, true);
    // A loop half the span across takes kTrimCellsPerLoop cells: twice that many steps.
    const int steps = int(2 * kTrimCellsPerLoop);
    EXPECT_EQ(nurbsTrimSteps(patch), (std::array<int, 2>{steps, steps}));
    const NurbsTessellation t = trimmed(patch);
    EXPECT_TRUE(t.warnings.empty());
    const double expected = 1.0 - kPi * r * r;
    std::printf("area %.5f, expected %.5f\n", area(t.mesh), expected);
    EXPECT_GE(area(t.mesh), expected);
    EXPECT_LE(area(t.mesh), expected + polygonAreaBound(1.0 / steps));
    // Every corner of a face lies outside the circle, or on it: on the polyline the curve is drawn
    // as, 16 chords a quarter at equal parameter steps, within the sagitta of the widest chord.
    double widest = 0.0;
    for (int k = 0; k < 16; ++k) {
        auto angle = [](double t) {  // the first quarter's rational quadratic
            const double a = (1 - t) * (1 - t), b = 2 * t * (1 - t) * kHalfRoot2, c = t * t;
            return std::atan2(b + c, a + b);
        };
        widest = std::max(widest, angle((k + 1) / 16.0) - angle(k / 16.0));
    }
    const double sagitta = r * (1.0 - std::cos(widest / 2)) + 1e-6;
    size_t onTheCircle = 0;
    for (int32_t index : t.mesh.faceVertexIndices) {
        const double du = t.mesh.points[3 * size_t(index)] - 0.5, dv = t.mesh.points[3 * size_t(index) + 1] - 0.5;
        const double d = std::sqrt(du * du + dv * dv);
        EXPECT_GE(d, r - sagitta) << "vertex " << index;
        if (d < r + 1e-6) ++onTheCircle;
    }
    // The circle crosses 2 steps / 2 grid lines each way twice: every crossing is a corner of the
    // two faces beside it.
    EXPECT_GE(onTheCircle, 2u * size_t(2 * steps));
}

TEST(NurbsTrim, OrientationDecidesTheSideKept) {
    const double r = 0.25, disc = kPi * r * r, h = 1.0 / (2 * kTrimCellsPerLoop);
    NurbsPatchInput island = square();
    addCircle(island.trimCurves, 0.5, 0.5, r, false);  // counter-clockwise alone: the disc is kept
    const double islandArea = area(trimmed(island).mesh);
    EXPECT_LE(islandArea, disc);
    EXPECT_GE(islandArea, disc - polygonAreaBound(h));

    NurbsPatchInput framed = square();
    addSquare(framed.trimCurves, 0.125, 0.875);         // an outer boundary inside the patch's own, on grid lines
    addCircle(framed.trimCurves, 0.5, 0.5, r, true);    // and a hole in it
    const double framedArea = area(trimmed(framed).mesh);
    EXPECT_GE(framedArea, 0.5625 - disc);
    EXPECT_LE(framedArea, 0.5625 - disc + polygonAreaBound(h));
}

// Seen closer, the grid refines so that the boundary's chords keep the surface's chord bound: a
// hole of radius R bends like a span of length L bending by L^2 / R, in object units.
TEST(NurbsTrim, TheBoundaryBendsLikeACurveOfItsRadius) {
    NurbsPatchInput patch = square();
    addCircle(patch.trimCurves, 0.5, 0.5, 0.25, true);
    const std::array<double, 2> bend = nurbsTrimBend(patch);
    EXPECT_NEAR(bend[0], 1.0 / 0.25, 1e-6);
    EXPECT_NEAR(bend[1], 1.0 / 0.25, 1e-6);
    for (float& x : patch.points) x *= 10.0f;  // ten times larger: L 10, R 2.5
    EXPECT_NEAR(nurbsTrimBend(patch)[0], 100.0 / 2.5, 1e-4);
    EXPECT_EQ(nurbsTrimBend(square()), (std::array<double, 2>{0.0, 0.0}));
}

// Weights so small that the points leave the doubles (valid data, being positive): they bound
// nothing, and the patch is drawn whole rather than the tessellation failing.
TEST(NurbsTrim, PointsBeyondTheDoublesBoundNothing) {
    NurbsPatchInput patch = square();
    addCircle(patch.trimCurves, 0.5, 0.5, 0.25, true);
    for (auto& point : patch.trimCurves.points) point[2] = 1e-320;
    EXPECT_NEAR(area(trimmed(patch).mesh), 1.0, 1e-6);
}

TEST(NurbsTrim, UntrimmedPatchIsTheWholeGrid) {
    const NurbsTessellation t = tessellateNurbsPatch(square(), nurbsTrimSteps(square()));
    EXPECT_EQ(t.mesh.faceVertexCounts, std::vector<int32_t>{4});
    EXPECT_NEAR(area(t.mesh), 1.0, 1e-6);
}

TEST(NurbsTrim, BadTrimDataIsNamed) {
    const std::vector<std::pair<std::function<void(NurbsTrimCurves&)>, std::string>> cases = {
        {[](NurbsTrimCurves& c) { c.counts = {2}; }, "trimCurve:orders has 1 values but trimCurve:counts adds up to 2 curves"},
        {[](NurbsTrimCurves& c) { c.counts = {0}; }, "trimCurve:counts[0] is 0"},
        {[](NurbsTrimCurves& c) { c.knots.pop_back(); }, "trimCurve:knots has 11 values but the curves' orders and vertex counts add up to 12"},
        {[](NurbsTrimCurves& c) { c.points.pop_back(); }, "trimCurve:points has 8 values but trimCurve:vertexCounts adds up to 9"},
        {[](NurbsTrimCurves& c) { c.points[3][2] = 0; }, "trimCurve:points[3] has weight 0"},
        {[](NurbsTrimCurves& c) { c.orders = {17}; }, "trimCurve:orders[0] is 17; it must be 2 to 16"},
        {[](NurbsTrimCurves& c) { c.knots[5] = -1; }, "the trimCurve:knots of curve 0 decrease at [5]"},
        {[](NurbsTrimCurves& c) { c.ranges = {{1, 9}}; }, "trimCurve:ranges[0] (1.000000, 9.000000) is not an increasing interval"},
    };
    for (const auto& [breakIt, expected] : cases) {
        NurbsPatchInput patch = square();
        addCircle(patch.trimCurves, 0.5, 0.5, 0.25, true);
        breakIt(patch.trimCurves);
        const std::string problem = nurbsPatchProblem(patch);
        EXPECT_NE(problem.find(expected), std::string::npos) << "got: " << problem;
    }
}

}  // namespace
}  // namespace obscura::delegate
