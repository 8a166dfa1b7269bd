// BasisCurves and Points through the ABI, against their geometry: a tube's silhouette is
// 2 f tan(asin(r / d)) wide and a ribbon facing the camera w f / d, a point's sphere covers the
// disc of radius f tan(asin(r / d)) and its depth at the centre is the pole's, the motion AOV of
// moving points is their displacement on screen, they instance through a PointInstancer, bad
// data skips only its prim with the prim named, and a tessellation over the cap is coarsened with
// a warning.
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
        // The centre's ray meets the sphere's pole (a vertex of the tessellation) at d - r: the
        // depth there is the true sphere's, to float precision.
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
    // One of 40 spheres holds the eye, so asks for the finest level, 512 segments: 40 x 512 x 510
    // triangles, over the 8 million cap; drawn at the next level down (the rest are seen).
    std::vector<std::array<float, 3>> points{{0, 0, 10.0f}};
    for (int i = 1; i < 40; ++i) points.push_back({float(i % 8) - 4.0f, float(i / 8) - 2.0f, -20.0f});
    host.addPrim("points", "/Cloud", {{"points", HostValue::points(points)}, {"widths", floats({1.0f})}});
    host.setInterpolation("/Cloud", "widths", OBSCURA_INTERPOLATION_CONSTANT);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    bool warned = false;
    for (const std::string& warning : host.loggedWarnings())
        warned |= warning.find("/Cloud: tessellation capped at 8000000 triangles") != std::string::npos;
    EXPECT_TRUE(warned);
    bool named = false;
    for (const std::string& warning : host.loggedWarnings())
        named |= warning.find(std::to_string(40u * 512u * 510u)) != std::string::npos &&
                 warning.find(std::to_string(40u * 256u * 254u)) != std::string::npos;
    EXPECT_TRUE(named) << "the warning names the triangles asked for and drawn";
    EXPECT_GT(pixelsOf(host.readInts("/Buffers/id"), primIdOf(host, "/Cloud")), 0);
}

}  // namespace
}  // namespace obscura::test
