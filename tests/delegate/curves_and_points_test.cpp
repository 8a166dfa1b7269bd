// BasisCurves and Points through the ABI, against their geometry: a tube's silhouette is
// 2 f tan(asin(r / d)) wide and a ribbon facing the camera w f / d, a point's sphere covers the
// disc of radius f tan(asin(r / d)) and its depth at the centre is the pole's, every pixel of a
// point seen close is the exact sphere's (sphere impostors) and its shadow the sphere's, the
// motion AOV of moving points is their displacement on screen, they instance through a
// PointInstancer, bad data skips only its prim with the prim named, and a tessellation over the
// cap is coarsened with a warning.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

constexpr int kSize = 127;  // odd: the centre pixel's centre is on the optical axis
constexpr float kFocalLength = 50.0f, kAperture = 20.955f;  // tenths of a scene unit
constexpr double kTanHalfFov = (kAperture / 2.0) / kFocalLength;
constexpr double kPixelsPerUnitAtUnitDistance = kSize / 2.0 / kTanHalfFov;

// A camera at (0, 0, distance) looking down -Z; no jitter, so ids and depths are the pixel centres'.
void addViewer(TestHost& host, double distance) {
    host.addCamera("/Camera", translation(0, 0, distance), kFocalLength, kAperture);
    setBool(host, "taa", false);
    host.addRenderBuffer("/Buffers/id", "int32", kSize, kSize);
    host.addRenderBuffer("/Buffers/depth", "float32", kSize, kSize);
}

HostValue floats(const std::vector<float>& v) {
    HostValue h;
    h.type = OBSCURA_VALUE_FLOAT;
    h.isArray = true;
    h.count = v.size();
    h.floats = v;
    return h;
}

int32_t primIdOf(TestHost& host, const char* path) {
    int32_t id = -2;
    EXPECT_EQ(host.api().getPrimId(host.delegate(), path, &id), OBSCURA_OK);
    return id;
}

int pixelsOf(const std::vector<int32_t>& ids, int32_t id) { return int(std::count(ids.begin(), ids.end(), id)); }

int columnPixels(const std::vector<int32_t>& ids, int x, int32_t id) {
    int count = 0;
    for (int y = 0; y < kSize; ++y) count += ids[size_t(y * kSize + x)] == id;
    return count;
}

// The test host's camera clipping range.
constexpr double kNear = 0.1, kFar = 1000.0;

// Hydra's clip-space depth of a point `z` ahead (Vulkan's [0, 1] range), and its inverse.
double clipDepth(double z) { return kFar * (z - kNear) / (z * (kFar - kNear)); }
double viewDistance(float depth) { return kNear * kFar / (kFar - double(depth) * (kFar - kNear)); }

// A straight curve along X through the origin, `width` wide (in `widthsName`).
void addStraightCurve(TestHost& host, const std::string& path, float width, bool ribbon,
                      const std::string& widthsName = "widths") {
    std::map<std::string, HostValue> values{{"points", HostValue::points({{-3, 0, 0}, {3, 0, 0}})},
                                            {"curveVertexCounts", HostValue::intArray({2})},
                                            {"type", HostValue::token("linear")},
                                            {widthsName, floats({width})}};
    if (ribbon) values["normals"] = HostValue::points({{0, 0, 1}});
    host.addPrim("basisCurves", path, values);
    host.setInterpolation(path, widthsName, OBSCURA_INTERPOLATION_CONSTANT);
    if (ribbon) host.setInterpolation(path, "normals", OBSCURA_INTERPOLATION_CONSTANT);
}

TEST(Curves, TubeWidthOnScreenIsItsSilhouetteAndItsDepthTheNearSide) {
    for (double distance : {8.0, 16.0}) {
        TestHost host;
        addViewer(host, distance);
        const float width = 0.6f;
        addStraightCurve(host, "/Wire", width, false);
        ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}, {"depth", "/Buffers/depth"}}), OBSCURA_OK)
            << host.lastError();
        auto ids = host.readInts("/Buffers/id");
        const int32_t wire = primIdOf(host, "/Wire");
        // A cylinder of radius r at distance d subtends 2 asin(r / d); on the image plane 2 f tan of half that.
        const double r = width / 2.0;
        const double expected = 2.0 * std::tan(std::asin(r / distance)) * kPixelsPerUnitAtUnitDistance;
        // Pixel centres sample the silhouette (within a pixel), chords within 2 x 0.25 px of it.
        EXPECT_NEAR(columnPixels(ids, kSize / 2 - 20, wire), expected, 1.0 + 2 * 0.5) << "at distance " << distance;
        // The ray through the centre meets the tube at its near side, r in front of the axis, up to
        // the chord's sagitta there (the level keeps it within 0.25 px on screen).
        const float depth = host.readFloats("/Buffers/depth")[size_t(kSize / 2 * kSize + kSize / 2)];
        const double sagitta = 0.25 / (kPixelsPerUnitAtUnitDistance / distance);
        EXPECT_NEAR(viewDistance(depth), distance - r, sagitta + 1e-4);
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    }
}

TEST(Curves, RibbonFacingTheCameraIsItsWidthOverDistanceWide) {
    for (const char* widthsName : {"widths", "primvars:widths"}) {
        TestHost host;
        const double distance = 10.0;
        addViewer(host, distance);
        const float width = 1.0f;
        addStraightCurve(host, "/Ribbon", width, true, widthsName);
        ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}, {"depth", "/Buffers/depth"}}), OBSCURA_OK)
            << host.lastError();
        auto ids = host.readInts("/Buffers/id");
        EXPECT_NEAR(columnPixels(ids, kSize / 2 + 10, primIdOf(host, "/Ribbon")),
                    width / distance * kPixelsPerUnitAtUnitDistance, 1.0)
            << widthsName;
        const float depth = host.readFloats("/Buffers/depth")[size_t(kSize / 2 * kSize + kSize / 2)];
        EXPECT_NEAR(viewDistance(depth), distance, 1e-3);
    }
}

TEST(Curves, MotionAovIsTheDisplacementOnScreen) {
    TestHost host;
    const double distance = 10.0, travel = 0.3;
    addViewer(host, distance);
    host.set("/Camera", "shutter:open", HostValue::doubleValue(-0.5));
    host.set("/Camera", "shutter:close", HostValue::doubleValue(0.5));
    setNumber(host, "timeCodesPerSecond", 1.0);
    host.addRenderBuffer("/Buffers/motion", "float32Vec3", kSize, kSize);
    addStraightCurve(host, "/Ribbon", 1.0f, true);
    host.set("/Ribbon", "velocities", HostValue::points({{0, float(travel), 0}, {0, float(travel), 0}}));
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}, {"motion", "/Buffers/motion"}}), OBSCURA_OK)
        << host.lastError();
    auto motion = host.readFloats("/Buffers/motion");
    const size_t centre = size_t(kSize / 2 * kSize + kSize / 2) * 3;
    // Up the image is -y in the motion AOV (y down).
    EXPECT_NEAR(motion[centre], 0.0, 0.05);
    EXPECT_NEAR(motion[centre + 1], -travel / distance * kPixelsPerUnitAtUnitDistance, 0.05);
}

TEST(Points, SphereSilhouetteAndDepthAtItsCentre) {
    for (double distance : {6.0, 12.0}) {
        TestHost host;
        addViewer(host, distance);
        const double radius = 1.0;
        host.addPrim("points", "/Dots", {{"points", HostValue::points({{0, 0, 0}})}, {"widths", floats({float(2 * radius)})}});
        ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}, {"depth", "/Buffers/depth"}}), OBSCURA_OK)
            << host.lastError();
        auto ids = host.readInts("/Buffers/id");
        const double expected = std::tan(std::asin(radius / distance)) * kPixelsPerUnitAtUnitDistance;
        EXPECT_NEAR(std::sqrt(pixelsOf(ids, primIdOf(host, "/Dots")) / kPi), expected, 0.5) << "at distance " << distance;
        // The centre's ray meets the sphere's pole at d - r: the depth there is the true sphere's,
        // to float precision.
        const float depth = host.readFloats("/Buffers/depth")[size_t(kSize / 2 * kSize + kSize / 2)];
        EXPECT_NEAR(depth, clipDepth(distance - radius), 4 * std::numeric_limits<float>::epsilon())
            << "at distance " << distance;
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    }
}

TEST(Points, MotionAovIsTheDisplacementOnScreen) {
    TestHost host;
    const double distance = 10.0, radius = 0.5, travel = 0.4;
    addViewer(host, distance);
    host.set("/Camera", "shutter:open", HostValue::doubleValue(-0.5));
    host.set("/Camera", "shutter:close", HostValue::doubleValue(0.5));
    setNumber(host, "timeCodesPerSecond", 1.0);
    host.addRenderBuffer("/Buffers/motion", "float32Vec3", kSize, kSize);
    host.addPrim("points", "/Dots",
                 {{"points", HostValue::points({{0, 0, 0}})},
                  {"widths", floats({float(2 * radius)})},
                  {"velocities", HostValue::points({{float(travel), 0, 0}})}});
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}, {"motion", "/Buffers/motion"}}), OBSCURA_OK)
        << host.lastError();
    auto motion = host.readFloats("/Buffers/motion");
    const size_t centre = size_t(kSize / 2 * kSize + kSize / 2) * 3;
    // The pole, at d - r from the eye, moves `travel` across the shutter.
    EXPECT_NEAR(motion[centre], travel / (distance - radius) * kPixelsPerUnitAtUnitDistance, 0.05);
    EXPECT_NEAR(motion[centre + 1], 0.0, 0.05);
}

TEST(CurvesAndPoints, EditsRetessellateAndEmptiedPrimsDrawNothing) {
    TestHost host;
    addViewer(host, 10.0);
    host.addPrim("points", "/Dots", {{"points", HostValue::points({{0, 0, 0}})}, {"widths", floats({1.0f})}});
    host.setInterpolation("/Dots", "widths", OBSCURA_INTERPOLATION_CONSTANT);
    addStraightCurve(host, "/Wire", 0.5f, false);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    const int32_t dots = primIdOf(host, "/Dots"), wire = primIdOf(host, "/Wire");
    const int before = pixelsOf(host.readInts("/Buffers/id"), dots);
    EXPECT_GT(before, 0);
    EXPECT_GT(pixelsOf(host.readInts("/Buffers/id"), wire), 0);
    // Twice the width: the disc's radius f tan(asin(r / d)) (nearly) doubles, its pixels (nearly) fourfold;
    // the tolerance is the pixels along the two rims (pixel centres sample them).
    host.set("/Dots", "widths", floats({2.0f}));
    host.api().markDirty(host.delegate(), "/Dots", OBSCURA_DIRTY_PARAMS);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    const double ratio = std::tan(std::asin(1.0 / 10.0)) / std::tan(std::asin(0.5 / 10.0));
    const double rims = 2 * kPi * (1.0 + 2.0) * std::tan(std::asin(0.5 / 10.0)) * kPixelsPerUnitAtUnitDistance;
    EXPECT_NEAR(pixelsOf(host.readInts("/Buffers/id"), dots), before * ratio * ratio, rims);
    host.set("/Dots", "points", HostValue::points({}));
    host.set("/Wire", "points", HostValue::points({}));
    host.set("/Wire", "curveVertexCounts", HostValue::intArray({}));
    host.api().markDirty(host.delegate(), "/Dots", OBSCURA_DIRTY_POINTS);
    host.api().markDirty(host.delegate(), "/Wire", OBSCURA_DIRTY_POINTS | OBSCURA_DIRTY_TOPOLOGY);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    EXPECT_EQ(pixelsOf(host.readInts("/Buffers/id"), dots), 0);
    EXPECT_EQ(pixelsOf(host.readInts("/Buffers/id"), wire), 0);
    EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
}

TEST(CurvesAndPoints, InstancedThroughAPointInstancer) {
    TestHost host;
    addViewer(host, 12.0);
    host.addPrim("points", "/Instancer/Prototypes/Dot",
                 {{"points", HostValue::points({{0, 0, 0}})}, {"widths", floats({1.0f})}});
    host.addPrim("instancer", "/Instancer",
                 {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Dot"})},
                  {"protoIndices", HostValue::intArray({0, 0})},
                  {"positions", HostValue::points({{-2.0f, 0, 0}, {2.0f, 0, 0}})}});
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    auto ids = host.readInts("/Buffers/id");
    const int32_t dot = primIdOf(host, "/Instancer/Prototypes/Dot");
    for (double x : {-2.0, 2.0}) {
        int px = int(kSize / 2.0 + x / 12.0 * kPixelsPerUnitAtUnitDistance);
        EXPECT_EQ(ids[size_t(kSize / 2 * kSize + px)], dot) << "instance at x " << x;
    }
    EXPECT_EQ(ids[size_t(kSize / 2 * kSize + kSize / 2)], -1);  // the prototype itself is not drawn
}

TEST(CurvesAndPoints, BadDataSkipsOnlyThatPrimAndNamesIt) {
    TestHost host;
    addViewer(host, 10.0);
    host.addPrim("basisCurves", "/WidthsCount",
                 {{"points", HostValue::points({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}})},
                  {"curveVertexCounts", HostValue::intArray({3})},
                  {"type", HostValue::token("linear")},
                  {"widths", floats({0.1f, 0.2f})}});
    host.addPrim("basisCurves", "/CountsSum",
                 {{"points", HostValue::points({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}})},
                  {"curveVertexCounts", HostValue::intArray({2, 2})},
                  {"type", HostValue::token("linear")}});
    host.addPrim("basisCurves", "/NegativeWidth",
                 {{"points", HostValue::points({{0, 0, 0}, {1, 0, 0}})},
                  {"curveVertexCounts", HostValue::intArray({2})},
                  {"type", HostValue::token("linear")},
                  {"widths", floats({0.1f, -0.2f})}});
    host.addPrim("points", "/PointWidths",
                 {{"points", HostValue::points({{0, 0, 0}, {1, 0, 0}})}, {"widths", floats({0.1f, 0.2f, 0.3f})}});
    addStraightCurve(host, "/Good", 0.5f, false);
    EXPECT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
    const std::vector<std::pair<std::string, std::string>> expected{
        {"/WidthsCount", "widths has 2 elements but its interpolation needs 3"},
        {"/CountsSum", "curveVertexCounts sum to 4 but there are 3 points"},
        {"/NegativeWidth", "widths[1] is -0.2"},
        {"/PointWidths", "widths has 3 elements but its interpolation needs 2"}};
    for (const auto& [path, message] : expected) host.expectError("skipped prim " + path + ": " + message);
    for (const auto& [path, message] : expected) {
        bool found = false;
        for (const std::string& error : host.loggedErrors())
            found |= error.find(path + ": " + message) != std::string::npos;
        EXPECT_TRUE(found) << path << ": " << message;
        EXPECT_EQ(pixelsOf(host.readInts("/Buffers/id"), primIdOf(host, path.c_str())), 0);
    }
    EXPECT_GT(pixelsOf(host.readInts("/Buffers/id"), primIdOf(host, "/Good")), 0);
}

TEST(CurvesAndPoints, TessellationOverTheCapIsCoarsenedWithAWarning) {
    TestHost host;
    addViewer(host, 10.0);
    // 5000 straight tubes; the eye inside the first asks for the finest level, 512 sides: 4 x 512 - 4
    // triangles a tube (sides x 2 along, two caps of sides - 2), over the 8 million cap; drawn at the
    // next level down.
    constexpr int kTubes = 5000;
    std::vector<std::array<float, 3>> points{{0, 0, 10.0f}, {0, 0, 9.0f}};
    for (int i = 1; i < kTubes; ++i) {
        const float x = float(i % 100) * 0.1f - 5.0f, y = float(i / 100) * 0.1f - 2.5f;
        points.push_back({x, y, -20.0f});
        points.push_back({x, y, -21.0f});
    }
    host.addPrim("basisCurves", "/Hair",
                 {{"points", HostValue::points(points)},
                  {"curveVertexCounts", HostValue::intArray(std::vector<int32_t>(kTubes, 2))},
                  {"type", HostValue::token("linear")},
                  {"widths", floats({0.05f})}});
    host.setInterpolation("/Hair", "widths", OBSCURA_INTERPOLATION_CONSTANT);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    bool warned = false;
    for (const std::string& warning : host.loggedWarnings())
        warned |= warning.find("/Hair: tessellation capped at 8000000 triangles") != std::string::npos;
    EXPECT_TRUE(warned);
    bool named = false;
    for (const std::string& warning : host.loggedWarnings())
        named |= warning.find(std::to_string(kTubes * (4u * 512u - 4u))) != std::string::npos &&
                 warning.find(std::to_string(kTubes * (4u * 256u - 4u))) != std::string::npos;
    EXPECT_TRUE(named) << "the warning names the triangles asked for and drawn";
    EXPECT_GT(pixelsOf(host.readInts("/Buffers/id"), primIdOf(host, "/Hair")), 0);
}

TEST(Points, OverTheCapAreSkippedAndNamed) {
    TestHost host;
    addViewer(host, 10.0);
    std::vector<std::array<float, 3>> points(666'667, {0.0f, 0.0f, 0.0f});
    host.addPrim("points", "/Cloud", {{"points", HostValue::points(points)}});
    addStraightCurve(host, "/Good", 0.5f, false);
    const std::string message = "/Cloud: 666667 points need 8000004 triangles, over the cap of 8000000 per prim";
    host.expectError("skipped prim " + message);
    EXPECT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
    bool named = false;
    for (const std::string& error : host.loggedErrors()) named |= error.find(message) != std::string::npos;
    EXPECT_TRUE(named);
    EXPECT_EQ(pixelsOf(host.readInts("/Buffers/id"), primIdOf(host, "/Cloud")), 0);
    EXPECT_GT(pixelsOf(host.readInts("/Buffers/id"), primIdOf(host, "/Good")), 0);
}

// Points are exact spheres, not tessellations: a unit sphere 6 units away (100 pixels across), every
// pixel centre whose line of sight meets the sphere is the point's and no other is (but within a
// thousandth of the radius of the rim), and the depth there is the nearer intersection's to
// 2e-4 units (a dozen float steps of the depth buffer there): 25 times tighter than a tessellation
// within a quarter pixel of the silhouette (its chords fall up to 0.25 / 51 of the radius inside the
// sphere). Under a non-uniform scale the sphere is the ellipsoid the scale makes of it, and a
// mirroring one (which turns the cube's faces inside out) changes nothing. With the eye
// inside the cube that bounds the sphere (its near faces behind the eye) the sphere is still seen
// whole, and with the eye inside the sphere its far side is.
TEST(Points, EveryPixelSeesTheExactSphere) {
    const double radius = 1.0;
    struct Case {
        std::array<double, 3> eye;
        double yScale;
        const char* name;
    };
    for (const Case& c : {Case{{0, 0, 6}, 1.0, "far"}, Case{{0, 0, 6}, 0.5, "squeezed"}, Case{{0, 0, 6}, -1.0, "mirrored"},
                          Case{{0.8, 0.8, 0.9}, 1.0, "eye in the cube"}, Case{{0.2, -0.1, 0.5}, 1.0, "eye in the sphere"}}) {
        TestHost host;
        host.addCamera("/Camera", translation(c.eye[0], c.eye[1], c.eye[2]), kFocalLength, kAperture);
        setBool(host, "taa", false);
        host.addRenderBuffer("/Buffers/id", "int32", kSize, kSize);
        host.addRenderBuffer("/Buffers/depth", "float32", kSize, kSize);
        host.addPrim("points", "/Dot", {{"points", HostValue::points({{0, 0, 0}})}, {"widths", floats({float(2 * radius)})}},
                     Matrix{1, 0, 0, 0, 0, c.yScale, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
        ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}, {"depth", "/Buffers/depth"}}), OBSCURA_OK)
            << host.lastError();
        const auto ids = host.readInts("/Buffers/id");
        const auto depths = host.readFloats("/Buffers/depth");
        const int32_t dot = primIdOf(host, "/Dot");
        const bool inside = c.eye[0] * c.eye[0] + c.eye[1] * c.eye[1] + c.eye[2] * c.eye[2] < radius * radius;
        int wrongCoverage = 0, wrongDepth = 0, covered = 0;
        double worstDepthError = 0.0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                // The line of sight through the pixel's centre, o + t d, in the unscaled sphere's
                // space: d's z is -1, so t is the view distance.
                const std::array<double, 3> o{c.eye[0], c.eye[1] / c.yScale, c.eye[2]};
                const std::array<double, 3> d{(x + 0.5 - kSize / 2.0) / (kSize / 2.0) * kTanHalfFov,
                                              (kSize / 2.0 - y - 0.5) / (kSize / 2.0) * kTanHalfFov / c.yScale, -1.0};
                const double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                const double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
                const double oo = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
                const double disc = b * b - a * (oo - radius * radius);
                const double closest = std::sqrt(std::max(0.0, oo - b * b / a));  // of the line to the centre
                const double t = (-b + (inside ? 1.0 : -1.0) * std::sqrt(std::max(disc, 0.0))) / a;
                const bool meets = disc >= 0.0 && t > kNear;
                const size_t pixel = size_t(y * kSize + x);
                if (std::abs(closest - radius) < 1e-3 * radius) continue;
                if (meets != (ids[pixel] == dot)) ++wrongCoverage;
                if (!meets || ids[pixel] != dot) continue;
                ++covered;
                const double error = std::abs(viewDistance(depths[pixel]) - t);
                worstDepthError = std::max(worstDepthError, error);
                wrongDepth += error > 2e-4;
            }
        EXPECT_GT(covered, 1000) << c.name;
        EXPECT_EQ(wrongCoverage, 0) << c.name;
        EXPECT_EQ(wrongDepth, 0) << c.name << ": worst depth error " << worstDepthError;
        std::printf("%s: %d pixels, worst depth error %.2e units\n", c.name, covered, worstDepthError);
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    }
}

// A point's shadow is its sphere's, not its cube's: a sphere of radius r at height h over the grey
// plane, lit by a distant light from above and to the side. A plane point whose line towards the
// light passes within 0.8 r of the centre is in shadow; one whose line passes beyond 1.2 r is lit
// (the cube's shadow reaches 1.73 r at its corners).
TEST(Points, ShadowIsTheSpheres) {
    LitPlaneScene scene;
    setBool(scene.host, "taa", false);
    const std::array<double, 3> toLight{-0.5 / std::sqrt(1.25), 0.0, 1.0 / std::sqrt(1.25)};
    scene.host.addPrim("distantLight", "/Sun",
                       {{"inputs:intensity", HostValue::floatValue(3.0f)},
                        {"inputs:normalize", HostValue::boolean(true)},
                        {"inputs:angle", HostValue::floatValue(0.0f)},
                        {"inputs:specular", HostValue::floatValue(0.0f)}},
                       lightPointingAlong({-toLight[0], -toLight[1], -toLight[2]}));
    const double radius = 0.25, height = 1.2;
    scene.host.addPrim("points", "/Dot",
                       {{"points", HostValue::points({{0, 0, float(height)}})}, {"widths", floats({float(2 * radius)})}});
    scene.host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    ASSERT_EQ(scene.host.render("/Camera", {{"color", "/Buffers/color"}, {"primId", "/Buffers/id"}}), OBSCURA_OK)
        << scene.host.lastError();
    const auto color = scene.host.readFloats("/Buffers/color");
    const auto ids = scene.host.readInts("/Buffers/id");
    const int32_t dot = primIdOf(scene.host, "/Dot");
    // Lit: Lambert under the light's irradiance at its incidence (no specular from this light).
    const double lit = kLitPlaneAlbedo / kPi * 3.0 * toLight[2];
    int shadowed = 0, litPixels = 0, wrong = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            if (ids[size_t(y * kWidth + x)] == dot) continue;
            const auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
            // Distance from the centre to the line p + s toLight.
            const std::array<double, 3> c{-p[0], -p[1], height - p[2]};
            const double along = c[0] * toLight[0] + c[1] * toLight[1] + c[2] * toLight[2];
            const double miss = std::sqrt(std::max(0.0, c[0] * c[0] + c[1] * c[1] + c[2] * c[2] - along * along)) / radius;
            const double radiance = color[(size_t(y) * kWidth + x) * 4 + 1];
            if (miss < 0.8) {
                ++shadowed;
                wrong += radiance > 0.05 * lit;
            } else if (miss > 1.2) {
                ++litPixels;
                wrong += std::abs(radiance - lit) > 0.05 * lit;
            }
        }
    EXPECT_GT(shadowed, 50);
    EXPECT_GT(litPixels, 1000);
    EXPECT_EQ(wrong, 0);
    EXPECT_TRUE(scene.host.loggedErrors().empty()) << scene.host.loggedErrors().front();
}

}  // namespace
}  // namespace obscura::test
