// NurbsCurves, HermiteCurves and TetMesh through the harness's scene host and the plugin, served
// as the Bezier basis curves and surface mesh they convert to: a rational NURBS circle's tube covers
// the annulus its radius and width say, a Hermite curve bulges where its tangents take it, a cube
// of six tets shows its outward faces, animated points and edited tangents
// are pulled again, and bad data skips only its prim, reported where it is authored. A camera at
// z = 5 whose view fills [-1.04775, 1.04775]^2 at z = 0 looks at them; a pixel is 0.033 wide there.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace obscura::test {
namespace {

constexpr double kHalfView = 1.04775;
constexpr double kPixel = 2.0 * kHalfView / kWidth;

// The point at z = 0 whose ray passes through the centre of pixel (column, row).
std::pair<double, double> planePointOf(int column, int row) {
    return {((column + 0.5) / kWidth * 2.0 - 1.0) * kHalfView, (1.0 - (row + 0.5) / kHeight * 2.0) * kHalfView};
}

float idAt(const std::vector<float>& ids, double x, double y) {
    const int column = int((x / kHalfView + 1.0) * kWidth / 2), row = int((1.0 - y / kHalfView) * kHeight / 2);
    return ids[size_t(row) * kWidth + size_t(column)];
}

int32_t primIdOf(HostedStage& scene, const char* path) {
    int32_t id = -2;
    EXPECT_EQ(scene.api().getPrimId(scene.delegate, path, &id), OBSCURA_OK);
    return id;
}

// A circle of `radius` about the origin in the XY plane as a rational quadratic NURBS curve (nine
// points on the square around it, the corners weighted sqrt(2) / 2), its tube 0.2 wide (a vertex
// width per point).
std::string nurbsCircle(const std::string& name, const std::string& points) {
    return "def NurbsCurves \"" + name + R"("
{
    point3f[] points)" + points + R"(
    int[] curveVertexCounts = [9]
    int[] order = [3]
    double[] knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]
    double[] pointWeights = [1, 0.70710678118654757, 1, 0.70710678118654757, 1, 0.70710678118654757, 1, 0.70710678118654757, 1]
    float[] widths = [0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2] (
        interpolation = "vertex"
    )
}
)";
}

std::string circlePoints(double r) {
    const double c[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    std::string text = "[";
    for (const auto& p : c)
        text += "(" + std::to_string(p[0] * r) + ", " + std::to_string(p[1] * r) + ", 0)" + (&p == &c[8] ? "]" : ", ");
    return text;
}

// Whether the tube of radius 0.1 around the circle of `radius` covers exactly the pixels it should:
// those whose centre's ray meets the plane z = 0 within 0.1 of the circle, up to a pixel at the
// silhouette (the tube's top and bottom seen in perspective widen it by 0.0013 at most).
void expectAnnulus(const std::vector<float>& ids, float id, double radius, const std::string& what) {
    int covered = 0, wrong = 0;
    for (int row = 0; row < kHeight; ++row)
        for (int column = 0; column < kWidth; ++column) {
            const auto [x, y] = planePointOf(column, row);
            const double off = std::abs(std::hypot(x, y) - radius);
            const bool drawn = ids[size_t(row) * kWidth + size_t(column)] == id;
            if (off < 0.1 - kPixel) covered += drawn, wrong += !drawn;
            if (off > 0.1 + 0.0013 + kPixel) wrong += drawn;
        }
    EXPECT_GT(covered, 100) << what;
    EXPECT_EQ(wrong, 0) << what;
}

TEST(ConvertedPrims, NurbsCircleTubeCoversItsAnnulusAndFollowsAnimatedPoints) {
    const std::string points = ".timeSamples = {\n        0: " + circlePoints(0.8) + ",\n        1: " + circlePoints(0.5) + ",\n    }";
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + nurbsCircle("Circle", points), "circle.usda"));
    auto ids = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(ids.size(), size_t(kWidth) * kHeight);
    const float circle = float(primIdOf(scene, "/Circle"));
    expectAnnulus(ids, circle, 0.8, "radius 0.8 at time 0");
    ASSERT_EQ(scene.host->markTimeVarying(scene.api(), scene.delegate), OBSCURA_OK);
    expectAnnulus(scene.renderAov("primId", 1, 1.0), circle, 0.5, "radius 0.5 at time 1");
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
}

// From (-0.8, 0) to (0.8, 0), leaving up and arriving down: x = -0.8 + 1.6 u, y = 2 (u - u^2) (the
// Hermite basis: the tangents' x parts make x linear, their y parts the bulge), 0.1 wide.
std::string hermiteArch(const std::string& tangents) {
    return "#usda 1.0\n" + usdaCamera() + R"(def HermiteCurves "Arch"
{
    point3f[] points = [(-0.8, 0, 0), (0.8, 0, 0)]
    vector3f[] tangents = )" + tangents + R"(
    int[] curveVertexCounts = [2]
    float[] widths = [0.1] (
        interpolation = "constant"
    )
}
)";
}

TEST(ConvertedPrims, HermiteCurveBulgesAlongItsTangentsAndFollowsTheirEdits) {
    HostedStage scene(usda::Stage::openFromString(hermiteArch("[(1.6, 2, 0), (1.6, -2, 0)]"), "arch.usda"));
    auto ids = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(ids.size(), size_t(kWidth) * kHeight);
    const float arch = float(primIdOf(scene, "/Arch"));
    EXPECT_EQ(idAt(ids, 0.0, 0.5), arch) << "u = 0.5";
    EXPECT_EQ(idAt(ids, -0.4, 0.375), arch) << "u = 0.25";
    EXPECT_NE(idAt(ids, 0.0, 0.0), arch) << "a straight line between its points";
    EXPECT_NE(idAt(ids, 0.0, 0.65), arch);
    // Tangents along the chord: the straight line.
    EXPECT_GE(scene.adopt(usda::Stage::openFromString(hermiteArch("[(1.6, 0, 0), (1.6, 0, 0)]"), "arch.usda")), 1u);
    ids = scene.renderAov("primId", 1, 0.0);
    EXPECT_EQ(idAt(ids, 0.0, 0.0), arch);
    EXPECT_NE(idAt(ids, 0.0, 0.5), arch);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
}

// The cube [-0.5, 0.5]^3 as six positively oriented tets around its diagonal (Kuhn's
// triangulation); point i is at the corner whose x, y, z are bits 0, 1, 2 of i.
const std::string kTetCube = R"(def TetMesh "Cube"
{
    point3f[] points = [(-0.5, -0.5, -0.5), (0.5, -0.5, -0.5), (-0.5, 0.5, -0.5), (0.5, 0.5, -0.5),
                        (-0.5, -0.5, 0.5), (0.5, -0.5, 0.5), (-0.5, 0.5, 0.5), (0.5, 0.5, 0.5)]
    int4[] tetVertexIndices = [(0, 1, 3, 7), (0, 5, 1, 7), (0, 3, 2, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 6, 4, 7)]
}
)";

TEST(ConvertedPrims, TetMeshIsItsSurfaceFacingOut) {
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + kTetCube, "cube.usda"));
    auto ids = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(ids.size(), size_t(kWidth) * kHeight);
    const float cube = float(primIdOf(scene, "/Cube"));
    // The front face (z = 0.5, 4.5 from the camera) spans 0.5 * 5 / 4.5 either side of the axis.
    const double half = 0.5 * 5.0 / 4.5;
    int wrong = 0;
    for (int row = 0; row < kHeight; ++row)
        for (int column = 0; column < kWidth; ++column) {
            const auto [x, y] = planePointOf(column, row);
            const double extent = std::max(std::abs(x), std::abs(y));
            const bool drawn = ids[size_t(row) * kWidth + size_t(column)] == cube;
            wrong += (extent < half - kPixel && !drawn) || (extent > half + kPixel && drawn);
        }
    EXPECT_EQ(wrong, 0);
    // Faces wound to face out: the front face's normal (eye space, here world space) points at the
    // camera; wound inwards, the normals computed from the winding would point away.
    const auto normals = scene.renderAov("normal", 3, 0.0);
    const float* n = &normals[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 3];
    EXPECT_GT(n[2], 0.9f * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
    // Twelve triangles: the two of each of the cube's six faces; the tets' inner faces are left out.
    ObscuraValue counts{};
    ASSERT_EQ(scene.host->sceneDelegate().getValue(scene.host->sceneDelegate().userData, "/Cube", "faceVertexCounts", 0.0,
                                                   &counts),
              OBSCURA_OK);
    EXPECT_EQ(counts.count, 12u);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_TRUE(scene.host->messages().empty()) << scene.host->messages().front().text;
}

TEST(ConvertedPrims, TetMeshUniformPrimvarsShadeItsSurfaceFaces) {
    // As Hydra draws a TetMesh (its surface faces' topology, its primvars as authored): a uniform
    // displayColor has one value per surface face, twelve triangles here. One per tet (six) does
    // not fit, is reported where authored and left out, and the prim is still drawn.
    std::string colours;
    for (int face = 0; face < 12; ++face) colours += std::string(face ? ", " : "") + "(0.2, 0.6, 0.9)";
    std::string cube = kTetCube;
    cube.insert(cube.rfind('}'), "    color3f[] primvars:displayColor = [" + colours + "] (interpolation = \"uniform\")\n");
    const std::string perTet = R"(def TetMesh "PerTet"
{
    point3f[] points = [(-2, -2, 0), (-1.5, -2, 0), (-2, -1.5, 0), (-2, -2, 0.5)]
    int4[] tetVertexIndices = [(0, 1, 2, 3)]
    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = "uniform")
}
)";
    const std::string text = "#usda 1.0\n" + usdaCamera() + cube + perTet;
    HostedStage scene(usda::Stage::openFromString(text, "tets.usda"));
    const auto albedo = scene.renderAov("albedo", 3, 0.0);
    const float* centre = &albedo[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 3];
    EXPECT_NEAR(centre[0], 0.2f, 0.01f);
    EXPECT_NEAR(centre[1], 0.6f, 0.01f);
    EXPECT_NEAR(centre[2], 0.9f, 0.01f);
    ASSERT_EQ(scene.host->messages().size(), 1u);
    const auto& message = scene.host->messages().front();
    EXPECT_NE(message.text.find("/PerTet"), std::string::npos) << message.text;
    EXPECT_NE(message.text.find("primvars:displayColor has 2 values but uniform interpolation needs 4"), std::string::npos)
        << message.text;
    EXPECT_EQ(message.where.line, int(std::count(text.begin(), text.begin() + long(text.find("color3f[] primvars:displayColor = [(1, 0")), '\n')) + 1);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

TEST(ConvertedPrims, BadDataSkipsOnlyItsPrimReportedWhereAuthored) {
    const std::string text = "#usda 1.0\n" + usdaCamera() + kTetCube + R"(def NurbsCurves "BadKnots"
{
    point3f[] points = [(-1, -1, 1), (-0.9, -0.9, 1), (-0.8, -0.9, 1), (-0.7, -1, 1)]
    int[] curveVertexCounts = [4]
    int[] order = [4]
    double[] knots = [0, 0, 0, 0, 1, 1, 1]
}
def HermiteCurves "BadTangents"
{
    point3f[] points = [(-1, 1, 1), (-0.7, 1, 1)]
    vector3f[] tangents = [(1, 0, 0)]
    int[] curveVertexCounts = [2]
}
def TetMesh "BadTets"
{
    point3f[] points = [(0.7, 0.7, 1), (0.9, 0.7, 1), (0.7, 0.9, 1), (0.7, 0.7, 1.2)]
    int4[] tetVertexIndices = [(0, 1, 2, 4)]
}
)";
    HostedStage scene(usda::Stage::openFromString(text, "bad.usda"));
    auto ids = scene.renderAov("primId", 1, 0.0);
    ASSERT_EQ(ids.size(), size_t(kWidth) * kHeight);
    EXPECT_EQ(idAt(ids, 0.0, 0.0), float(primIdOf(scene, "/Cube"))) << "the good prim renders";
    const int badPixels = int(std::count_if(ids.begin(), ids.end(), [&](float id) {
        return id == float(primIdOf(scene, "/BadKnots")) || id == float(primIdOf(scene, "/BadTangents")) ||
               id == float(primIdOf(scene, "/BadTets"));
    }));
    EXPECT_EQ(badPixels, 0);
    auto lineOf = [&](const std::string& fragment) {
        return int(std::count(text.begin(), text.begin() + long(text.find(fragment)), '\n')) + 1;
    };
    const struct {
        const char* message;
        const char* authored;
    } expected[] = {
        {"/BadKnots: knots has 7 values but the curves need 8 (vertex count + order each); not drawn", "double[] knots"},
        {"/BadTangents: tangents has 1 values but there are 2 points (one tangent each); not drawn", "vector3f[] tangents = [(1"},
        {"/BadTets: tetVertexIndices[0] names point 4, outside the 4 points; not drawn", "int4[] tetVertexIndices = [(0, 1, 2, 4"},
    };
    ASSERT_EQ(scene.host->messages().size(), 3u);
    for (const auto& [message, authored] : expected) {
        const auto found = std::find_if(scene.host->messages().begin(), scene.host->messages().end(),
                                        [&](const harness::HostMessage& m) { return m.text == message; });
        ASSERT_NE(found, scene.host->messages().end()) << message;
        EXPECT_FALSE(found->error);
        EXPECT_EQ(found->where.file, "bad.usda");
        EXPECT_EQ(found->where.line, lineOf(authored)) << message;
    }
    EXPECT_FALSE(scene.warned("not supported"));
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
}

TEST(ConvertedPrims, FramingBoundsHoldTheConvertedPrims) {
    // No camera: the framing camera looks at the bounds of what is drawn.
    const std::string text = "#usda 1.0\n" + kTetCube + R"(def HermiteCurves "Arch"
{
    point3f[] points = [(10, 0, 0), (12, 0, 0)]
    vector3f[] tangents = [(0, 30, 0), (0, -30, 0)]
    int[] curveVertexCounts = [2]
}
)";
    auto opened = usda::Stage::openFromString(text, "bounds.usda");
    ASSERT_TRUE(std::holds_alternative<std::unique_ptr<usda::Stage>>(opened));
    harness::UsdSceneHost host(*std::get<std::unique_ptr<usda::Stage>>(opened));
    const harness::SceneBounds bounds = host.bounds(0.0);
    // x from the cube's -0.5 to the arch's 12; y up to the arch's inner control points at 30 / 3.
    EXPECT_NEAR(bounds.centre[0], 5.75, 1e-9);
    EXPECT_NEAR(bounds.centre[1], 4.75, 1e-9);
    EXPECT_TRUE(host.messages().empty()) << host.messages().front().text;
}

}  // namespace
}  // namespace obscura::test
