// NurbsPatch prims from USD text through the harness's scene host and the plugin: a rational
// sphere's silhouette is the cone of half-angle asin(r / d) seen from the camera and its normals
// are the sphere's, the polygons follow the size on screen, trim curves cut their holes, and bad
// data skips only its prim.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace obscura::test {
namespace {

// A NurbsPatch of radius `radius` at the origin: the rational quadratic circle (The NURBS Book,
// ex. 7.2) swept along a half circle from the south pole. `extra`: lines added to its body.
std::string nurbsSphere(const std::string& name, double radius, const std::string& extra = "") {
    const double h = std::sqrt(0.5);
    const double circle[9][3] = {{1, 0, 1}, {1, 1, h}, {0, 1, 1}, {-1, 1, h}, {-1, 0, 1}, {-1, -1, h}, {0, -1, 1}, {1, -1, h}, {1, 0, 1}};
    const double profile[5][3] = {{0, -1, 1}, {1, -1, h}, {1, 0, 1}, {1, 1, h}, {0, 1, 1}};  // radial, z, weight
    std::ostringstream points, weights;
    for (const auto& p : profile)
        for (const auto& c : circle) {
            points << "(" << radius * c[0] * p[0] << ", " << radius * c[1] * p[0] << ", " << radius * p[1] << "), ";
            weights << c[2] * p[2] << ", ";
        }
    return "def NurbsPatch \"" + name + "\"\n{\n"
           "    int uVertexCount = 9\n    int vVertexCount = 5\n    int uOrder = 3\n    int vOrder = 3\n"
           "    double[] uKnots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]\n"
           "    double[] vKnots = [0, 0, 0, 1, 1, 2, 2, 2]\n"
           "    point3f[] points = [" + points.str() + "]\n"
           "    double[] pointWeights = [" + weights.str() + "]\n" + extra + "}\n";
}

size_t count(const std::vector<float>& ids, float id) { return size_t(std::count(ids.begin(), ids.end(), id)); }

TEST(NurbsPatch, SphereSilhouetteIsTheConeOfHalfAngleAsinRadiusOverDistanceAndItsNormalsTheSpheres) {
    const double radius = 0.8, distance = 5.0, tanHalfFov = 1.04775 / 5.0;  // usdaCamera's view
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + nurbsSphere("Ball", radius), "ball.usda"));
    scene.setBool("taa", false);  // pixel centres: the silhouette is sampled, not filtered
    const std::vector<float> ids = scene.renderAov("primId", 1);
    const float ball = ids[size_t(kHeight / 2 * kWidth + kWidth / 2)];
    ASSERT_GE(ball, 0.0f);
    const double expected = std::tan(std::asin(radius / distance)) / tanHalfFov * (kWidth / 2.0);
    EXPECT_NEAR(std::sqrt(double(count(ids, ball)) / kPi), expected, 0.5);
    // Eye space is world space for this camera: at a pixel (x, y) the sphere's normal is the
    // direction from its centre to where the pixel's ray meets it.
    const std::vector<float> normals = scene.renderAov("normal", 3);
    for (const auto& [x, y] : {std::pair{kWidth / 2, kHeight / 2}, std::pair{kWidth / 2 + 15, kHeight / 2 - 9}}) {
        const std::array<double, 3> on = planePointAtPixel(x, y, 1.0, tanHalfFov);  // the ray's direction at depth 1
        const std::array<double, 3> d{on[0], on[1], -1.0};
        const double dd = d[0] * d[0] + d[1] * d[1] + 1.0, b = -distance;  // |o + t d|^2 = r^2, o = (0, 0, 5)
        const double t = (-b - std::sqrt(b * b - dd * (distance * distance - radius * radius))) / dd;
        const std::array<double, 3> hit{t * d[0], t * d[1], distance - t};
        for (size_t k = 0; k < 3; ++k)
            EXPECT_NEAR(normals[size_t(y * kWidth + x) * 3 + k], hit[k] / radius, 0.02) << "pixel " << x << "," << y;
    }
    EXPECT_FALSE(scene.warned("not supported"));
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
}

HostValue floatArray(const std::vector<float>& values) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT;
    h.isArray = true;
    h.floats = values;
    h.count = values.size();
    return h;
}

// The triangles drawn of a bicubic dome 2 units across at `distance` from the camera, each of
// three frames (the count must not change while the view does not).
std::vector<uint64_t> domeTriangles(double distance) {
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, distance), 50.0f, 20.955f);
    host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    std::vector<std::array<float, 3>> points;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            points.push_back({i * 2.0f / 3 - 1, j * 2.0f / 3 - 1, (i % 3 ? 0.8f : 0.0f) * (j % 3 ? 1.0f : 0.5f)});
    const std::vector<float> bezier{0, 0, 0, 0, 1, 1, 1, 1};
    host.addPrim("nurbsPatch", "/Dome",
                 {{"points", HostValue::points(points)},
                  {"uVertexCount", HostValue::intValue(4)},
                  {"vVertexCount", HostValue::intValue(4)},
                  {"uOrder", HostValue::intValue(4)},
                  {"vOrder", HostValue::intValue(4)},
                  {"uKnots", floatArray(bezier)},
                  {"vKnots", floatArray(bezier)}});
    std::vector<uint64_t> counts;
    for (int frame = 0; frame < 3; ++frame) {
        EXPECT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
        counts.push_back(renderStats(host).trianglesDrawn);
    }
    EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    return counts;
}

TEST(NurbsPatch, PolygonsFollowTheSizeOnScreenAndRepeat) {
    const std::vector<uint64_t> far = domeTriangles(200.0), near = domeTriangles(4.0);
    EXPECT_EQ(far[0], far[2]);
    EXPECT_EQ(near[0], near[2]);
    EXPECT_GT(far[0], 0u);
    EXPECT_LT(far[0], near[0]);
}

TEST(NurbsPatch, BadDataSkipsOnlyThatPrimAndNamesIt) {
    const std::string bad = "def NurbsPatch \"Bad\"\n{\n    int uVertexCount = 2\n    int vVertexCount = 2\n"
                            "    int uOrder = 2\n    int vOrder = 2\n    double[] uKnots = [0, 0, 1]\n"
                            "    double[] vKnots = [0, 0, 1, 1]\n    point3f[] points = [(-1, -1, 1), (1, -1, 1), (-1, 1, 1), (1, 1, 1)]\n}\n";
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + bad + nurbsSphere("Good", 0.5), "bad.usda"));
    scene.expectError("/Bad: uKnots has 3 values but uVertexCount + uOrder is 4");
    const std::vector<float> ids = scene.renderAov("primId", 1);
    ASSERT_EQ(scene.errors.size(), 1u);
    // The good sphere behind the bad square's place draws.
    EXPECT_GE(ids[size_t(kHeight / 2 * kWidth + kWidth / 2)], 0.0f);
}

// A bilinear square 1 unit across whose points move 0.2 along X between time codes 0 and 1.
std::string movingSquare() {
    return "def NurbsPatch \"Square\"\n{\n    int uVertexCount = 2\n    int vVertexCount = 2\n    int uOrder = 2\n"
           "    int vOrder = 2\n    double[] uKnots = [0, 0, 1, 1]\n    double[] vKnots = [0, 0, 1, 1]\n"
           "    point3f[] points.timeSamples = {\n"
           "        0: [(-0.5, -0.5, 0), (0.5, -0.5, 0), (-0.5, 0.5, 0), (0.5, 0.5, 0)],\n"
           "        1: [(-0.3, -0.5, 0), (0.7, -0.5, 0), (-0.3, 0.5, 0), (0.7, 0.5, 0)],\n    }\n}\n";
}

TEST(NurbsPatch, DeformingWithinTheShutterIsItsMotion) {
    // The shutter spans time codes 0 to 1 around the frame at 0.5 (timeCodesPerSecond 1).
    HostedStage scene(usda::Stage::openFromString(
        "#usda 1.0\n(\n    timeCodesPerSecond = 1\n)\n" +
            usdaCamera("    double shutter:open = -0.5\n    double shutter:close = 0.5\n") + movingSquare(),
        "moving.usda"));
    const std::vector<float> motion = scene.renderAov("motion", 3, 0.5);
    ASSERT_EQ(motion.size(), size_t(kWidth) * kHeight * 3);
    // 0.2 units at the focus distance's view of 2 x 1.04775 units across kWidth pixels.
    const double expected = 0.2 * kWidth / (2.0 * 1.04775);
    const size_t centre = size_t(kHeight / 2 * kWidth + kWidth / 2) * 3;
    EXPECT_NEAR(motion[centre], expected, 0.05 * expected);
    EXPECT_NEAR(motion[centre + 1], 0.0, 0.05 * expected);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

TEST(NurbsPatch, InstancedThroughAPointInstancer) {
    const std::string instancer = "def PointInstancer \"Scatter\"\n{\n"
                                  "    rel prototypes = [</Scatter/Prototypes/Ball>]\n"
                                  "    int[] protoIndices = [0, 0]\n"
                                  "    point3f[] positions = [(-0.5, 0, 0), (0.5, 0, 0)]\n"
                                  "    def Scope \"Prototypes\"\n    {\n" +
                                  nurbsSphere("Ball", 0.25) + "    }\n}\n";
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + instancer, "scatter.usda"));
    const std::vector<float> ids = scene.renderAov("primId", 1);
    auto idAt = [&](double x) { return ids[size_t(kHeight / 2 * kWidth + int((x / 1.04775 + 1.0) * kWidth / 2))]; };
    EXPECT_GE(idAt(-0.5), 0.0f);
    EXPECT_GE(idAt(0.5), 0.0f);
    EXPECT_LT(idAt(0.0), 0.0f);  // between them: nothing
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

// A square 1 unit across facing the camera, its (u, v) its (x, y) from its lower left corner, with
// a round hole of radius 0.25 in its middle cut by a clockwise trim circle (homogeneous points).
std::string squareWithHole(const std::string& name, const std::string& trimExtra = "") {
    const double h = std::sqrt(0.5);
    const double p[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    std::ostringstream points;
    for (int i = 0; i < 9; ++i) {
        const double w = i % 2 == 0 ? 1.0 : h;
        points << "(" << (0.5 + 0.25 * p[i][0]) * w << ", " << (0.5 - 0.25 * p[i][1]) * w << ", " << w << "), ";
    }
    return "def NurbsPatch \"" + name + "\"\n{\n    int uVertexCount = 2\n    int vVertexCount = 2\n    int uOrder = 2\n"
           "    int vOrder = 2\n    double[] uKnots = [0, 0, 1, 1]\n    double[] vKnots = [0, 0, 1, 1]\n"
           "    point3f[] points = [(-0.5, -0.5, 0), (0.5, -0.5, 0), (-0.5, 0.5, 0), (0.5, 0.5, 0)]\n"
           "    int[] trimCurve:counts = [1]\n    int[] trimCurve:orders = [3]\n    int[] trimCurve:vertexCounts = [9]\n"
           "    double[] trimCurve:knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]\n    double2[] trimCurve:ranges = [(0, 4)]\n"
           "    double3[] trimCurve:points = [" + points.str() + "]\n" + trimExtra + "}\n";
}

TEST(NurbsPatch, TrimCurvesCutTheirHole) {
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + squareWithHole("Holed"), "holed.usda"));
    scene.setBool("taa", false);
    const std::vector<float> ids = scene.renderAov("primId", 1);
    // Pixels across the middle row at x units from the centre (usdaCamera's 1.04775 units half-width).
    auto idAt = [&](double x) { return ids[size_t(kHeight / 2 * kWidth + int((x / 1.04775 + 1.0) * kWidth / 2))]; };
    EXPECT_LT(idAt(0.0), 0.0f);    // the hole
    EXPECT_LT(idAt(0.2), 0.0f);
    EXPECT_LT(idAt(-0.2), 0.0f);
    EXPECT_GE(idAt(0.32), 0.0f);   // the square around it
    EXPECT_GE(idAt(-0.32), 0.0f);
    EXPECT_LT(idAt(0.6), 0.0f);    // beyond the square
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

TEST(NurbsPatch, MalformedTrimCurvesSkipOnlyThatPrimAndNameIt) {
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() +
                                                      squareWithHole("Bad", "    int[] trimCurve:counts = [2]\n") +
                                                      nurbsSphere("Good", 0.1),
                                                  "badtrim.usda"));
    scene.expectError("/Bad: trimCurve:orders has 1 values but trimCurve:counts adds up to 2 curves");
    const std::vector<float> ids = scene.renderAov("primId", 1);
    ASSERT_EQ(scene.errors.size(), 1u);
    EXPECT_GE(ids[size_t(kHeight / 2 * kWidth + kWidth / 2)], 0.0f);  // the good sphere
    EXPECT_LT(ids[size_t(kHeight / 2 * kWidth + kWidth * 7 / 10)], 0.0f);  // the bad square is not drawn
}

}  // namespace
}  // namespace obscura::test
