// Geometry lands where projection says: a known triangle covers exactly the pixels whose
// centres it contains, and the primId AOV returns the ids of the prims drawn there.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

// An orthographic camera whose aperture maps one scene unit to 8 pixels of a 64x64 image.
void addOrthoCamera(TestHost& host) {
    host.addPrim("camera", "/Ortho",
                 {{"projection", HostValue::token("orthographic")},
                  {"horizontalAperture", HostValue::floatValue(80.0f)},  // tenths of a unit: 8 units
                  {"verticalAperture", HostValue::floatValue(80.0f)},
                  {"clippingRange", HostValue::float2(0.1f, 100.0f)}},
                 translation(0, 0, 10));
}

// Pixel centre in scene units: x right, y up, origin in the image centre.
std::array<double, 2> pixelCentre(int x, int y) { return {(x + 0.5 - 32) / 8.0, (32 - (y + 0.5)) / 8.0}; }

double edge(std::array<double, 2> a, std::array<double, 2> b, std::array<double, 2> p) {
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

TEST(Coverage, KnownTriangleCoversThePixelsItContains) {
    TestHost host;
    addOrthoCamera(host);
    const std::array<double, 2> a{-3.1, -2.3}, b{2.7, -1.05}, c{-0.45, 3.3};
    host.addPrim("mesh", "/Triangle",
                 {{"points", HostValue::points({{float(a[0]), float(a[1]), 0}, {float(b[0]), float(b[1]), 0},
                                                {float(c[0]), float(c[1]), 0}})},
                  {"faceVertexCounts", HostValue::intArray({3})},
                  {"faceVertexIndices", HostValue::intArray({0, 1, 2})}});
    host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    ASSERT_EQ(host.render("/Ortho", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    int32_t id = -2;
    ASSERT_EQ(host.api().getPrimId(host.delegate(), "/Triangle", &id), OBSCURA_OK);
    auto ids = host.readInts("/Buffers/id");
    int inside = 0, checked = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            auto p = pixelCentre(x, y);
            double e0 = edge(a, b, p), e1 = edge(b, c, p), e2 = edge(c, a, p);
            // Pixels whose centre lies on an edge (within float error) follow the tie rule; skip them.
            double margin = 1e-3;
            bool in = e0 > margin && e1 > margin && e2 > margin;
            bool out = e0 < -margin || e1 < -margin || e2 < -margin;
            if (!in && !out) continue;
            ++checked;
            inside += in;
            EXPECT_EQ(ids[size_t(y) * kWidth + x], in ? id : -1) << "pixel " << x << ", " << y;
        }
    EXPECT_GT(inside, 300);
    EXPECT_GT(checked, 4000);
}

TEST(PrimId, ReturnsTheIdsOfThePrimsDrawn) {
    TestHost host;
    addOrthoCamera(host);
    addPlane(host, "/Left", "", 1.0, translation(-2, 0, 0));
    addPlane(host, "/Right", "", 1.0, translation(2, 0, 0));
    addPlane(host, "/Hidden", "", 1.0, translation(0, 2.5, 0));
    host.set("/Hidden", "visibility", HostValue::token("invisible"));
    host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    ASSERT_EQ(host.render("/Ortho", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    int32_t left = -2, right = -2, hidden = -2;
    ASSERT_EQ(host.api().getPrimId(host.delegate(), "/Left", &left), OBSCURA_OK);
    ASSERT_EQ(host.api().getPrimId(host.delegate(), "/Right", &right), OBSCURA_OK);
    ASSERT_EQ(host.api().getPrimId(host.delegate(), "/Hidden", &hidden), OBSCURA_OK);
    EXPECT_NE(left, right);
    auto ids = host.readInts("/Buffers/id");
    auto at = [&](double sx, double sy) {
        int x = int(sx * 8 + 32), y = int(32 - sy * 8);
        return ids[size_t(y) * kWidth + x];
    };
    EXPECT_EQ(at(-2.0, 0.0), left);
    EXPECT_EQ(at(2.0, 0.0), right);
    EXPECT_EQ(at(0.0, 0.0), -1);
    EXPECT_EQ(at(0.0, 2.5), -1) << "an invisible prim draws nothing";
    for (int32_t v : ids) EXPECT_TRUE(v == -1 || v == left || v == right);
}

TEST(Aovs, DepthNormalAndAlbedoFollowHydraConventions) {
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, 5));
    addMaterial(host, "/Looks/Paint", {0.2f, 0.4f, 0.6f});
    addPlane(host, "/Plane", "/Looks/Paint");
    host.addRenderBuffer("/Buffers/depth", "float32", kWidth, kHeight);
    host.addRenderBuffer("/Buffers/normal", "float32Vec3", kWidth, kHeight);
    host.addRenderBuffer("/Buffers/albedo", "float32Vec3", kWidth, kHeight);
    ASSERT_EQ(host.render("/Camera", {{"depth", "/Buffers/depth"}, {"normal", "/Buffers/normal"},
                                      {"albedo", "/Buffers/albedo"}}),
              OBSCURA_OK)
        << host.lastError();
    auto depth = host.readFloats("/Buffers/depth");
    auto normal = host.readFloats("/Buffers/normal");
    auto albedo = host.readFloats("/Buffers/albedo");
    size_t centre = 32 * kWidth + 32;
    // Clip-space depth of a point 5 units ahead with near 0.1 and far 1000 (Vulkan [0,1] range).
    double n = 0.1, f = 1000.0, z = 5.0;
    double expectedDepth = (f / (n - f) * -z + n * f / (n - f)) / z;
    EXPECT_NEAR(depth[centre], expectedDepth, 1e-5);
    // Eye-space normal of a plane facing the camera is +Z (Hydra's Neye).
    EXPECT_NEAR(normal[centre * 3 + 2], 1.0f, 0.01f);
    EXPECT_NEAR(normal[centre * 3 + 0], 0.0f, 0.01f);
    // Albedo goes through 8-bit sRGB storage.
    EXPECT_NEAR(albedo[centre * 3 + 0], 0.2f, 0.01f);
    EXPECT_NEAR(albedo[centre * 3 + 1], 0.4f, 0.01f);
    EXPECT_NEAR(albedo[centre * 3 + 2], 0.6f, 0.01f);
}

}  // namespace
}  // namespace obscura::test
