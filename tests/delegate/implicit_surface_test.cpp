// Implicit gprims through the ABI: a sphere's silhouette is the cone of half-angle asin(r / d)
// seen from the camera, a cube's faces have their own normals, the tessellation grows with the
// size on screen and is the same from render to render, and bad parameters skip only their prim.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

constexpr int kSize = 128;
constexpr float kFocalLength = 50.0f, kAperture = 20.955f;  // tenths of a scene unit
constexpr double kTanHalfFov = (kAperture / 2.0) / kFocalLength;

// A camera at (0, 0, distance) looking down -Z; no jitter, so ids and normals are the pixel centres'.
void addViewer(TestHost& host, double distance) {
    host.addCamera("/Camera", translation(0, 0, distance), kFocalLength, kAperture);
    setBool(host, "taa", false);
    host.addRenderBuffer("/Buffers/id", "int32", kSize, kSize);
    host.addRenderBuffer("/Buffers/normal", "float32Vec3", kSize, kSize);
}

int32_t primIdOf(TestHost& host, const char* path) {
    int32_t id = -2;
    EXPECT_EQ(host.api().getPrimId(host.delegate(), path, &id), OBSCURA_OK);
    return id;
}

int pixelsOf(const std::vector<int32_t>& ids, int32_t id) { return int(std::count(ids.begin(), ids.end(), id)); }

TEST(ImplicitSurface, SphereSilhouetteIsTheConeOfHalfAngleAsinRadiusOverDistance) {
    for (double distance : {6.0, 12.0}) {
        TestHost host;
        const double radius = 1.0;
        addViewer(host, distance);
        host.addPrim("sphere", "/Ball", {{"radius", HostValue::doubleValue(radius)}});
        ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
        auto ids = host.readInts("/Buffers/id");
        // The silhouette on the image plane is a circle of radius f tan(asin(r / d)).
        const double expected = std::tan(std::asin(radius / distance)) / kTanHalfFov * (kSize / 2.0);
        const double measured = std::sqrt(pixelsOf(ids, primIdOf(host, "/Ball")) / kPi);
        EXPECT_NEAR(measured, expected, 0.5) << "at distance " << distance;
        // Across the centre row, the diameter: within a pixel (pixel centres sample it), plus at
        // each end the chords' distance from the true silhouette (at most twice the quarter pixel
        // the level is chosen for: implicit_tessellation.h).
        int row = 0;
        for (int x = 0; x < kSize; ++x) row += ids[size_t(kSize / 2 * kSize + x)] == primIdOf(host, "/Ball");
        EXPECT_NEAR(row, 2.0 * expected, 1.0 + 2 * 0.5);
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    }
}

TEST(ImplicitSurface, CubeFacesHaveTheirOwnNormals) {
    TestHost host;
    addViewer(host, 8.0);
    // Turned 45 degrees about Y (row vectors): the +Z face turns right, the -X face left.
    const double c = std::cos(kPi / 4), s = std::sin(kPi / 4);
    host.addPrim("cube", "/Box", {{"size", HostValue::doubleValue(2.0)}},
                 Matrix{c, 0, -s, 0, 0, 1, 0, 0, s, 0, c, 0, 0, 0, 0, 1});
    ASSERT_EQ(host.render("/Camera", {{"normal", "/Buffers/normal"}}), OBSCURA_OK) << host.lastError();
    auto normals = host.readFloats("/Buffers/normal");
    auto normalAt = [&](int x, int y) {
        const float* n = &normals[size_t(y * kSize + x) * 3];
        return std::array<double, 3>{n[0], n[1], n[2]};
    };
    // Eye space is world space for this camera. The face edge runs down the image centre.
    for (auto [x, expectedX] : {std::pair{kSize / 2 - 8, -s}, {kSize / 2 + 8, s}}) {
        auto n = normalAt(x, kSize / 2);
        EXPECT_NEAR(n[0], expectedX, 0.02) << "x " << x;
        EXPECT_NEAR(n[1], 0.0, 0.02);
        EXPECT_NEAR(n[2], c, 0.02);
    }
}

TEST(ImplicitSurface, TessellationFollowsTheSizeOnScreenAndRepeats) {
    auto trianglesAt = [](double distance, std::vector<int32_t>* ids = nullptr) {
        TestHost host;
        addViewer(host, distance);
        host.addPrim("sphere", "/Ball", {{"radius", HostValue::doubleValue(1.0)}});
        std::vector<uint64_t> counts;
        for (int frame = 0; frame < 3; ++frame) {
            EXPECT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
            counts.push_back(renderStats(host).trianglesDrawn);
            auto frameIds = host.readInts("/Buffers/id");
            if (ids && frame > 0) EXPECT_EQ(frameIds, *ids) << "frame " << frame << " differs";
            if (ids) *ids = frameIds;
        }
        EXPECT_EQ(counts[0], counts[1]);
        EXPECT_EQ(counts[1], counts[2]);
        return counts[0];
    };
    std::vector<int32_t> ids;
    const uint64_t far = trianglesAt(200.0), middle = trianglesAt(20.0, &ids), near = trianglesAt(3.0);
    EXPECT_LT(far, middle);
    EXPECT_LT(middle, near);
}

TEST(ImplicitSurface, BadParametersSkipOnlyThatPrim) {
    TestHost host;
    host.expectError("skipped prim /Bad: radius");
    addViewer(host, 10.0);
    host.addPrim("sphere", "/Bad", {{"radius", HostValue::doubleValue(-1.0)}});
    host.addPrim("cube", "/Good", {{"size", HostValue::doubleValue(2.0)}});
    EXPECT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
    ASSERT_FALSE(host.loggedErrors().empty());
    const std::string& error = host.loggedErrors().back();
    EXPECT_NE(error.find("/Bad"), std::string::npos) << error;
    EXPECT_NE(error.find("radius"), std::string::npos) << error;
    auto ids = host.readInts("/Buffers/id");
    EXPECT_GT(pixelsOf(ids, primIdOf(host, "/Good")), 0);
    EXPECT_EQ(pixelsOf(ids, primIdOf(host, "/Bad")), 0);
}

TEST(ImplicitSurface, InstancedThroughAPointInstancer) {
    TestHost host;
    addViewer(host, 12.0);
    host.addPrim("sphere", "/Instancer/Prototypes/Ball", {{"radius", HostValue::doubleValue(0.5)}});
    host.addPrim("instancer", "/Instancer",
                 {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Ball"})},
                  {"protoIndices", HostValue::intArray({0, 0})},
                  {"positions", HostValue::points({{-2.0f, 0, 0}, {2.0f, 0, 0}})}});
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    auto ids = host.readInts("/Buffers/id");
    const int32_t ball = primIdOf(host, "/Instancer/Prototypes/Ball");
    // Each instance's centre: x = +-2 at distance 12 projects to +-2 / 12 / tan(half fov) of the half width.
    for (double x : {-2.0, 2.0}) {
        int px = int(kSize / 2.0 + x / 12.0 / kTanHalfFov * kSize / 2.0);
        EXPECT_EQ(ids[size_t(kSize / 2 * kSize + px)], ball) << "instance at x " << x;
    }
    EXPECT_EQ(ids[size_t(kSize / 2 * kSize + kSize / 2)], -1);  // the prototype itself is not drawn
}

}  // namespace
}  // namespace obscura::test
