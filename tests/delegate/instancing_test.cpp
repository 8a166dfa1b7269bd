// PointInstancer: prototypes drawn once per instance (GPU instancing), placed by USD's
// scale-orient-translate order in the instancer's space; prototypes never draw on their own; an
// instancer in another's prototype places its prototypes within each of the other's instances.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

// Orthographic camera: one scene unit = 8 pixels of a 64x64 image, centred on the origin.
struct InstancedScene {
    TestHost host;
    int32_t square = -1, bar = -1;
    InstancedScene() {
        host.addPrim("camera", "/Ortho",
                     {{"projection", HostValue::token("orthographic")},
                      {"horizontalAperture", HostValue::floatValue(80.0f)},
                      {"verticalAperture", HostValue::floatValue(80.0f)},
                      {"clippingRange", HostValue::float2(0.1f, 100.0f)}},
                     translation(0, 0, 10));
        addPlane(host, "/Instancer/Prototypes/Square", "", 0.5);
        // A bar 2 units wide and 0.5 high: shows rotation.
        host.addPrim("mesh", "/Instancer/Prototypes/Bar",
                     {{"points", HostValue::points({{-1, -0.25f, 0}, {1, -0.25f, 0}, {1, 0.25f, 0}, {-1, 0.25f, 0}})},
                      {"faceVertexCounts", HostValue::intArray({4})},
                      {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                      {"subdivisionScheme", HostValue::token("none")}});
        const float s = std::sqrt(0.5f);
        host.addPrim("instancer", "/Instancer",
                     {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Square", "/Instancer/Prototypes/Bar"})},
                      {"protoIndices", HostValue::intArray({0, 0, 1, 0})},
                      {"positions", HostValue::points({{-2.5f, 2.5f, 0}, {2.5f, 2.5f, 0}, {0, -2.0f, 0}, {0, 0, 0}})},
                      // The bar turns 90 degrees about Z: (w, x, y, z) real part first.
                      {"orientations", HostValue::float4Array({{1, 0, 0, 0}, {1, 0, 0, 0}, {s, 0, 0, s}, {1, 0, 0, 0}})},
                      {"scales", HostValue::points({{1, 1, 1}, {2, 2, 1}, {1, 1, 1}, {1, 1, 1}})},
                      {"invisibleIds", HostValue::intArray({3})}},
                     translation(0.5, 0, 0));
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    }
    std::vector<int32_t> render(ObscuraStatus expected = OBSCURA_OK) {
        EXPECT_EQ(host.render("/Ortho", {{"primId", "/Buffers/id"}}), expected) << host.lastError();
        host.api().getPrimId(host.delegate(), "/Instancer/Prototypes/Square", &square);
        host.api().getPrimId(host.delegate(), "/Instancer/Prototypes/Bar", &bar);
        return host.readInts("/Buffers/id");
    }
};

int32_t at(const std::vector<int32_t>& ids, double sx, double sy) {
    int x = int(std::floor(sx * 8 + 32)), y = int(std::floor(32 - sy * 8));
    return ids[size_t(y) * kWidth + x];
}

TEST(Instancing, InstancesAreDrawnWhereUsdPlacesThem) {
    InstancedScene s;
    auto ids = s.render();
    // Instancer translated by +0.5 in x.
    EXPECT_EQ(at(ids, -2.0, 2.5), s.square);
    EXPECT_EQ(at(ids, -2.0 + 0.6, 2.5), -1) << "unit square: half-size 0.5";
    EXPECT_EQ(at(ids, 3.0 + 0.9, 2.5), s.square) << "scaled x2: half-size 1";
    // The rotated bar is tall and thin around (0.5, -2).
    EXPECT_EQ(at(ids, 0.5, -2.0 + 0.9), s.bar);
    EXPECT_EQ(at(ids, 0.5 + 0.9, -2.0), -1);
    // Instance 3 is invisible; prototypes draw nothing at their own place.
    EXPECT_EQ(at(ids, 0.5, 0.0), -1);
    EXPECT_EQ(at(ids, 0.05, 0.05), -1);
    ObscuraRenderStats stats = renderStats(s.host);
    EXPECT_EQ(stats.trianglesDrawn, 6u) << "3 visible instances of 2-triangle meshes";
}

// The instanceId AOV names each instance by its index in the instancer's arrays (so a host can
// pick an instance as usdview does); a mesh drawn once and the background are -1.
TEST(Instancing, InstanceIdNamesTheInstanceIndex) {
    InstancedScene s;
    addPlane(s.host, "/Plain", "", 0.5, translation(-2.5, -2.5, 0));
    s.host.addRenderBuffer("/Buffers/instance", "int32", kWidth, kHeight);
    ASSERT_EQ(s.host.render("/Ortho", {{"primId", "/Buffers/id"}, {"instanceId", "/Buffers/instance"}}), OBSCURA_OK)
        << s.host.lastError();
    std::vector<int32_t> instances = s.host.readInts("/Buffers/instance");
    EXPECT_EQ(at(instances, -2.0, 2.5), 0);
    EXPECT_EQ(at(instances, 3.0 + 0.9, 2.5), 1);
    EXPECT_EQ(at(instances, 0.5, -2.0 + 0.9), 2) << "the bar: index 2 of the arrays, the first of its prototype";
    EXPECT_EQ(at(instances, 0.5, 0.0), -1) << "instance 3 is invisible";
    EXPECT_EQ(at(instances, -2.5, -2.5), -1) << "a mesh drawn once";
    EXPECT_EQ(at(instances, -3.9, -0.5), -1) << "nothing drawn";
    std::vector<int32_t> ids = s.host.readInts("/Buffers/id");
    int32_t plain = -1;
    ASSERT_EQ(s.host.api().getPrimId(s.host.delegate(), "/Plain", &plain), OBSCURA_OK);
    EXPECT_EQ(at(ids, -2.5, -2.5), plain);
    // Hiding instance 0 leaves the others their indices.
    s.host.set("/Instancer", "invisibleIds", HostValue::intArray({0}));
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Instancer", OBSCURA_DIRTY_VISIBILITY), OBSCURA_OK);
    ASSERT_EQ(s.host.render("/Ortho", {{"instanceId", "/Buffers/instance"}}), OBSCURA_OK) << s.host.lastError();
    instances = s.host.readInts("/Buffers/instance");
    EXPECT_EQ(at(instances, -2.0, 2.5), -1);
    EXPECT_EQ(at(instances, 3.0, 2.5), 1);
    EXPECT_EQ(at(instances, 0.5, 0.0), 3);
}

TEST(Instancing, ManyInstancesShareOneMesh) {
    InstancedScene s;
    const int n = 100000;
    std::vector<int32_t> proto(n, 0);
    std::vector<std::array<float, 3>> positions(n);
    for (int i = 0; i < n; ++i) positions[size_t(i)] = {float(i % 317) * 0.01f - 1.5f, float(i / 317) * 0.01f - 1.5f, 0};
    s.host.set("/Instancer", "protoIndices", HostValue::intArray(proto));
    s.host.set("/Instancer", "positions", HostValue::points(positions));
    s.host.set("/Instancer", "orientations", HostValue::float4Array({}));
    s.host.set("/Instancer", "scales", HostValue::points({}));
    s.host.set("/Instancer", "invisibleIds", HostValue::intArray({}));
    auto ids = s.render();
    ObscuraRenderStats stats = renderStats(s.host);
    EXPECT_EQ(stats.trianglesDrawn, uint64_t(n) * 2);
    EXPECT_EQ(at(ids, 0.0, 0.0), s.square);
}

TEST(Instancing, BadInstanceDataSkipsTheInstancer) {
    InstancedScene s;
    s.host.expectError("skipped prim /Instancer: protoIndices[2] = 5");
    s.host.expectError("skipped prim /Instancer: positions has 1 entries for 4 instances");
    s.host.set("/Instancer", "protoIndices", HostValue::intArray({0, 0, 5, 0}));
    auto ids = s.render(OBSCURA_ERROR_BAD_PRIM_DATA);
    EXPECT_NE(s.host.lastError().find("protoIndices[2]"), std::string::npos) << s.host.lastError();
    s.host.set("/Instancer", "protoIndices", HostValue::intArray({0, 0, 1, 0}));
    s.host.set("/Instancer", "positions", HostValue::points({{0, 0, 0}}));
    s.host.api().markDirty(s.host.delegate(), "/Instancer", OBSCURA_DIRTY_ALL);
    s.render(OBSCURA_ERROR_BAD_PRIM_DATA);
    EXPECT_NE(s.host.lastError().find("positions"), std::string::npos) << s.host.lastError();
}

// An instancer of two squares (x = -1 and 1) sits 1 up in the prototype of an instancer of two
// rows (y = -2 and 1.5), itself moved 0.5 along x: four squares, at x = -0.5 and 1.5, y = -1 and
// 2.5. Nothing is drawn where either instancer alone would put a square.
struct NestedScene : InstancedScene {
    NestedScene() {
        addPlane(host, "/Outer/Protos/Row/Protos/Tile", "", 0.25);
        host.addPrim("instancer", "/Outer/Protos/Row",
                     {{"prototypes", HostValue::paths({"/Outer/Protos/Row/Protos/Tile"})},
                      {"protoIndices", HostValue::intArray({0, 0})},
                      {"positions", HostValue::points({{-1, 0, 0}, {1, 0, 0}})}},
                     translation(0, 1, 0));
        host.addPrim("instancer", "/Outer",
                     {{"prototypes", HostValue::paths({"/Outer/Protos/Row"})},
                      {"protoIndices", HostValue::intArray({0, 0})},
                      {"positions", HostValue::points({{0, -2, 0}, {0, 1.5f, 0}})}},
                     translation(0.5, 0, 0));
    }
    int32_t tile() {
        int32_t id = -2;
        host.api().getPrimId(host.delegate(), "/Outer/Protos/Row/Protos/Tile", &id);
        return id;
    }
};

TEST(Instancing, NestedInstancersPlaceTheirPrototypesInEveryOuterInstance) {
    NestedScene s;
    auto ids = s.render();
    const int32_t tile = s.tile();
    for (double x : {-0.5, 1.5})
        for (double y : {-1.0, 2.5}) EXPECT_EQ(at(ids, x, y), tile) << "a tile at " << x << ", " << y;
    int tiles = 0;
    for (int32_t id : ids) tiles += id == tile;
    EXPECT_EQ(tiles, 4 * 4 * 4) << "four tiles of 4 x 4 pixels, none elsewhere";
    EXPECT_NE(at(ids, -1.0, 1.0), tile) << "where the inner instancer alone would put one";
    EXPECT_NE(at(ids, 0.5, -2.0), tile) << "where the outer instancer alone would put one";
}

TEST(Instancing, AHiddenNestedInstancerHidesItsPrototypesInEveryOuterInstance) {
    NestedScene s;
    s.host.set("/Outer/Protos/Row", "visibility", HostValue::token("invisible"));
    auto ids = s.render();
    const int32_t tile = s.tile();
    EXPECT_EQ(std::count(ids.begin(), ids.end(), tile), 0);
}

}  // namespace
}  // namespace obscura::test
