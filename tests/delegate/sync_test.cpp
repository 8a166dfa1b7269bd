// Incremental sync: a render pulls only what the dirty bits name (callbacks counted per prim).
#include "schemas/schema.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <span>
#include <thread>
#include <tuple>

namespace obscura::test {
namespace {

struct TwoPlanes {
    TestHost host;
    TwoPlanes() {
        host.addCamera("/Camera", translation(0, 0, 12));
        addMaterial(host, "/Looks/A", {0.5f, 0.5f, 0.5f});
        addMaterial(host, "/Looks/B", {0.5f, 0.1f, 0.1f});
        addPlane(host, "/A", "/Looks/A", 1.0, translation(-1.5, 0, 0));
        addPlane(host, "/B", "/Looks/B", 1.0, translation(1.5, 0, 0));
        host.addPrim("distantLight", "/Sun", {{"inputs:normalize", HostValue::boolean(true)}},
                     lightPointingAlong({0, 0, -1}));
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
    }
    ObscuraStatus render() { return host.render("/Camera", {{"color", "/Buffers/color"}}); }
    uint32_t synced() { return renderStats(host).primsSynced; }
};

TEST(Sync, FirstRenderPullsEverythingThenNothing) {
    TwoPlanes t;
    ASSERT_EQ(t.render(), OBSCURA_OK) << t.host.lastError();
    EXPECT_EQ(t.synced(), 7u);
    EXPECT_GT(t.host.getValueCalls["/A"], 3);
    t.host.resetCounters();
    ASSERT_EQ(t.render(), OBSCURA_OK);
    EXPECT_EQ(t.synced(), 0u);
    EXPECT_TRUE(t.host.getValueCalls.empty());
}

TEST(Sync, DirtyPointsPullOnlyThatPrimsPoints) {
    TwoPlanes t;
    ASSERT_EQ(t.render(), OBSCURA_OK);
    t.host.resetCounters();
    ASSERT_EQ(t.host.api().markDirty(t.host.delegate(), "/A", OBSCURA_DIRTY_POINTS), OBSCURA_OK);
    ASSERT_EQ(t.render(), OBSCURA_OK);
    EXPECT_EQ(t.synced(), 1u);
    EXPECT_EQ(t.host.getValueCalls.size(), 1u);
    EXPECT_EQ(t.host.getValueCalls["/A"], 1);  // points only
}

TEST(Sync, ASubdividedMeshFollowsItsPointsWhenTheyStartToMove) {
    // A subdivided mesh drops its refiner after its first refinement (it may never refine again);
    // points that then change refine through a new one, kept from there on. A quad's Catmull-Clark
    // limit with sharp corners (edgeAndCorner) is the quad: it covers the pixels the same quad
    // without subdivision covers, at every size it takes.
    auto quad = [](float h) { return HostValue::points({{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}}); };
    auto scene = [&](TestHost& host, const char* scheme, float h) {
        host.addCamera("/Camera", translation(0, 0, 12));
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
        setBool(host, "taa", false);  // every frame through the pixel centres
        host.addPrim("mesh", "/Patch",
                     {{"points", quad(h)},
                      {"faceVertexCounts", HostValue::intArray({4})},
                      {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                      {"subdivisionScheme", HostValue::token(scheme)},
                      {"obscura:refineLevel", HostValue::intValue(2)}});
    };
    auto covered = [](TestHost& host) {
        EXPECT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
        auto ids = host.readInts("/Buffers/id");
        return std::count_if(ids.begin(), ids.end(), [](int32_t id) { return id >= 0; });
    };
    auto flat = [&](float h) {
        TestHost host;
        scene(host, "none", h);
        return covered(host);
    };
    TestHost host;
    scene(host, "catmullClark", 2.0f);
    EXPECT_EQ(covered(host), flat(2.0f));
    for (float h : {1.0f, 1.5f, 1.0f}) {
        host.set("/Patch", "points", quad(h));
        host.api().markDirty(host.delegate(), "/Patch", OBSCURA_DIRTY_POINTS);
        EXPECT_EQ(covered(host), flat(h)) << "half size " << h;
    }
}

TEST(Sync, DirtyTransformPullsNoAttributes) {
    TwoPlanes t;
    ASSERT_EQ(t.render(), OBSCURA_OK);
    t.host.resetCounters();
    t.host.setTransform("/B", translation(1.5, 1.0, 0));
    ASSERT_EQ(t.host.api().markDirty(t.host.delegate(), "/B", OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    ASSERT_EQ(t.render(), OBSCURA_OK);
    EXPECT_EQ(t.synced(), 1u);
    EXPECT_TRUE(t.host.getValueCalls.empty());
}

TEST(Sync, DirtyMaterialChangesTheImage) {
    TwoPlanes t;
    ASSERT_EQ(t.render(), OBSCURA_OK);
    auto before = t.host.readFloats("/Buffers/color");
    t.host.resetCounters();
    t.host.set("/Looks/B", "inputs:diffuseColor", HostValue::float3(0.1f, 0.5f, 0.1f));
    ASSERT_EQ(t.host.api().markDirty(t.host.delegate(), "/Looks/B", OBSCURA_DIRTY_PARAMS), OBSCURA_OK);
    ASSERT_EQ(t.render(), OBSCURA_OK);
    EXPECT_EQ(t.synced(), 1u);
    EXPECT_EQ(t.host.getValueCalls.count("/A"), 0u);
    EXPECT_EQ(t.host.getValueCalls.count("/B"), 0u);
    auto after = t.host.readFloats("/Buffers/color");
    // The right plane (material B) turned green; the left one is unchanged.
    size_t right = (32 * kWidth + 44) * 4, left = (32 * kWidth + 20) * 4;
    EXPECT_GT(after[right + 1], before[right + 1] * 2);
    EXPECT_EQ(after[left + 1], before[left + 1]);
}

TEST(Sync, RemovedPrimStopsDrawing) {
    TwoPlanes t;
    t.host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    ASSERT_EQ(t.host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK);
    int32_t idA = -1;
    t.host.api().getPrimId(t.host.delegate(), "/A", &idA);
    ASSERT_EQ(t.host.api().removePrim(t.host.delegate(), "/A"), OBSCURA_OK);
    ASSERT_EQ(t.host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK);
    for (int32_t v : t.host.readInts("/Buffers/id")) EXPECT_NE(v, idA);
    EXPECT_EQ(t.host.api().removePrim(t.host.delegate(), "/A"), OBSCURA_ERROR_NOT_FOUND);
}

TEST(Delegates, SeveralLiveAndRenderOnTheirOwnThreads) {
    TwoPlanes first, second;
    ObscuraStatus a = OBSCURA_ERROR_INTERNAL, b = OBSCURA_ERROR_INTERNAL;
    std::thread t1([&] { a = first.render(); });
    std::thread t2([&] { b = second.render(); });
    t1.join();
    t2.join();
    EXPECT_EQ(a, OBSCURA_OK);
    EXPECT_EQ(b, OBSCURA_OK);
    EXPECT_EQ(first.host.readFloats("/Buffers/color"), second.host.readFloats("/Buffers/color"));
}

}  // namespace
}  // namespace obscura::test

namespace obscura::test {
namespace {

uint64_t geometryBytes(TestHost& host) { return renderStats(host).geometryBytes; }

TEST(SharedGeometry, IdenticalMeshesAreStoredOnce) {
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, 30));
    host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    addPlane(host, "/Copy0", "", 0.5, translation(-4, 3.5, 0));
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    const uint64_t one = geometryBytes(host);
    ASSERT_GT(one, 0u);
    // Repeated references of one asset: same points and topology, other transforms.
    for (int i = 1; i < 50; ++i) addPlane(host, "/Copy" + std::to_string(i), "", 0.5, translation(-4 + (i % 9), i / 9 - 3, 0));
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    EXPECT_EQ(geometryBytes(host), one);
    // Every copy still draws where its own transform puts it.
    auto ids = host.readInts("/Buffers/id");
    std::set<int32_t> seen(ids.begin(), ids.end());
    EXPECT_EQ(seen.size(), 51u) << "50 copies and the background";
    // A copy whose points change gets its own storage; the others keep sharing.
    host.set("/Copy7", "points", HostValue::points({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}));
    host.api().markDirty(host.delegate(), "/Copy7", OBSCURA_DIRTY_POINTS);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK);
    EXPECT_EQ(geometryBytes(host), 2 * one);
    // Removing every copy but one releases the shared storage only when the last user goes.
    for (int i = 1; i < 50; ++i) host.api().removePrim(host.delegate(), ("/Copy" + std::to_string(i)).c_str());
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK);
    EXPECT_EQ(geometryBytes(host), one);
}

TEST(SharedGeometry, CopiesOfASubdividedMeshShareOneStorageAndEachReportsItsOwnProblems) {
    // Repeated references of one asset share their refined, built mesh (their inputs are equal);
    // each still draws where its transform puts it and reports what its data lacks under its own
    // path (a subdivided mesh's primvar of the wrong count too, which refinement leaves out).
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, 12));
    host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    setBool(host, "taa", false);
    auto addCopy = [&](const std::string& path, double x) {
        host.addPrim("mesh", path,
                     {{"points", HostValue::points({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}})},
                      {"faceVertexCounts", HostValue::intArray({4})},
                      {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                      {"subdivisionScheme", HostValue::token("catmullClark")},
                      {"primvars:displayColor", HostValue::points({{1, 0, 0}, {0, 1, 0}})}},  // vertex needs 4
                     translation(x, 0, 0));
    };
    addCopy("/Left", -1.2);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    const uint64_t one = geometryBytes(host);
    addCopy("/Right", 1.2);
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    EXPECT_EQ(geometryBytes(host), one);
    auto ids = host.readInts("/Buffers/id");
    // Each square (0.8 wide) sits on its own side of the frame's centre column.
    std::set<int32_t> left, right;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (int32_t id = ids[size_t(y * kWidth + x)]; id >= 0) (x < kWidth / 2 ? left : right).insert(id);
    ASSERT_EQ(left.size(), 1u);
    ASSERT_EQ(right.size(), 1u);
    EXPECT_NE(*left.begin(), *right.begin());
    for (const std::string path : {"/Left", "/Right"}) {
        const auto& warnings = host.loggedWarnings();
        EXPECT_EQ(std::count_if(warnings.begin(), warnings.end(),
                                [&](const std::string& w) {
                                    return w.rfind(path + ": primvars:displayColor has 2 elements", 0) == 0;
                                }),
                  1)
            << path;
    }
}

TEST(SharedGeometry, CopiesThatDifferInAPrimvarKeepTheirOwn) {
    // Same points and topology, another displayColor: not a copy, each draws its own colour.
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, 10));
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
    host.addPrim("distantLight", "/Sun", {{"inputs:normalize", HostValue::boolean(true)}}, lightPointingAlong({0, 0, -1}));
    for (const auto& [path, x, colour] : {std::tuple{"/Red", -1.0, std::array<float, 3>{1, 0, 0}},
                                          std::tuple{"/Blue", 1.0, std::array<float, 3>{0, 0, 1}}}) {
        addPlane(host, path, "", 0.8, translation(x, 0, 0));
        host.set(path, "primvars:displayColor", HostValue::points({colour}));
        host.setInterpolation(path, "primvars:displayColor", OBSCURA_INTERPOLATION_CONSTANT);
    }
    ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    auto color = host.readFloats("/Buffers/color");
    // The camera sees +-2.1 units at z = 0 across 64 pixels: x = -1 is pixel 16.7, x = +1 pixel 47.3.
    const float* red = &color[(32 * kWidth + 16) * 4];
    const float* blue = &color[(32 * kWidth + 47) * 4];
    EXPECT_GT(red[0], 3.0f * red[2]);  // the fallback material's white specular adds to both
    EXPECT_GT(blue[2], 3.0f * blue[0]);
}

TEST(SharedGeometry, CopiesThatDifferInASubdivisionTagKeepTheirOwn) {
    // The same control mesh, one copy with its face a hole: that copy draws nothing.
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, 10));
    host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    for (const auto& [path, x] : {std::pair{"/Whole", -1.0}, std::pair{"/Holed", 1.0}}) {
        addPlane(host, path, "", 0.8, translation(x, 0, 0));
        host.set(path, "subdivisionScheme", HostValue::token("catmullClark"));
    }
    host.set("/Holed", "holeIndices", HostValue::intArray({0}));
    ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << host.lastError();
    auto ids = host.readInts("/Buffers/id");
    // The camera sees +-2.1 units at z = 0 across 64 pixels: x = -1 is pixel 16.7, x = +1 pixel 47.3.
    EXPECT_GE(ids[size_t(32 * kWidth + 16)], 0);
    EXPECT_LT(ids[size_t(32 * kWidth + 47)], 0);
}

TEST(SharedGeometry, InstancedCopiesKeepTheirOwnMaterialAndId) {
    // Repeated references become one instanced draw; each instance still reads its own record.
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, 10));
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
    host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    addMaterial(host, "/Looks/Red", {0, 0, 0}, 1.0f, 0.0f, {1.0f, 0.0f, 0.0f});
    addMaterial(host, "/Looks/Blue", {0, 0, 0}, 1.0f, 0.0f, {0.0f, 0.0f, 1.0f});
    addPlane(host, "/Left", "/Looks/Red", 0.8, translation(-1, 0, 0));
    addPlane(host, "/Right", "/Looks/Blue", 0.8, translation(1, 0, 0));
    ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}, {"primId", "/Buffers/id"}}), OBSCURA_OK)
        << host.lastError();
    auto color = host.readFloats("/Buffers/color");
    auto ids = host.readInts("/Buffers/id");
    // The camera sees +-2.1 units at z = 0 across 64 pixels: x = -1 is pixel 16.7, x = +1 pixel 47.3.
    const float* left = &color[(32 * kWidth + 16) * 4];
    const float* right = &color[(32 * kWidth + 47) * 4];
    EXPECT_FLOAT_EQ(left[0], 1.0f);
    EXPECT_FLOAT_EQ(left[2], 0.0f);
    EXPECT_FLOAT_EQ(right[0], 0.0f);
    EXPECT_FLOAT_EQ(right[2], 1.0f);
    int32_t leftId = 0, rightId = 0;
    ASSERT_EQ(host.api().getPrimId(host.delegate(), "/Left", &leftId), OBSCURA_OK);
    ASSERT_EQ(host.api().getPrimId(host.delegate(), "/Right", &rightId), OBSCURA_OK);
    EXPECT_EQ(ids[32 * kWidth + 16], leftId);
    EXPECT_EQ(ids[32 * kWidth + 47], rightId);
}

}  // namespace
}  // namespace obscura::test

namespace obscura::test {
namespace {

// 48 small quads, a sphere and a quad with NaN points, seen from the front; the host declares its
// callbacks thread-safe or not.
struct ManyPrims {
    TestHost host;
    explicit ManyPrims(bool threadSafeCallbacks) : host(true, threadSafeCallbacks) {
        host.expectError("skipped prim /Bad: points: element 0 is NaN");
        host.addCamera("/Camera", translation(0, 0, 20));
        addMaterial(host, "/Looks/Grey", {0.5f, 0.5f, 0.5f});
        host.addPrim("distantLight", "/Sun", {{"inputs:normalize", HostValue::boolean(true)}},
                     lightPointingAlong({0, 0, -1}));
        for (int i = 0; i < 48; ++i)
            addPlane(host, "/Planes/P" + std::to_string(i), "/Looks/Grey", 0.3, translation(i % 8 - 3.5, i / 8 - 2.5, 0));
        host.addPrim("sphere", "/Ball", {{"radius", HostValue::doubleValue(0.5)}}, translation(0, 0, 2));
        addPlane(host, "/Bad", "", 0.3, translation(0, -3.5, 0));
        const float nan = std::numeric_limits<float>::quiet_NaN();
        host.set("/Bad", "points", HostValue::points({{nan, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    }
    ObscuraStatus render() {
        return host.render("/Camera", {{"color", "/Buffers/color"}, {"primId", "/Buffers/id"}});
    }
};

TEST(ParallelSync, AThreadSafeHostIsCalledOnSeveralThreadsAndTheFrameIsTheSame) {
    ManyPrims serial(false), parallel(true);
    // The first callback for a quad waits (10 s at most) until another thread calls for one: two
    // rprims pull at once (the camera, light and material pull first, on the calling thread).
    std::mutex mutex;
    std::condition_variable arrived;
    std::set<std::thread::id> seen;
    parallel.host.onGetValue = [&](const std::string& path, const std::string&) {
        if (path.rfind("/Planes/", 0) != 0) return;
        std::unique_lock lock(mutex);
        const bool first = seen.empty();
        seen.insert(std::this_thread::get_id());
        arrived.notify_all();
        if (first) arrived.wait_for(lock, std::chrono::seconds(10), [&] { return seen.size() > 1; });
    };
    ASSERT_EQ(serial.render(), OBSCURA_ERROR_BAD_PRIM_DATA) << serial.host.lastError();
    ASSERT_EQ(parallel.render(), OBSCURA_ERROR_BAD_PRIM_DATA) << parallel.host.lastError();
    EXPECT_GT(parallel.host.callbackThreads.size(), 1u);
    // Messages still come on the thread that called render.
    EXPECT_EQ(parallel.host.logThreads, std::set<std::thread::id>{std::this_thread::get_id()});
    EXPECT_EQ(parallel.host.getValueCalls, serial.host.getValueCalls);
    EXPECT_EQ(renderStats(parallel.host).primsSynced, renderStats(serial.host).primsSynced);
    EXPECT_EQ(parallel.host.readFloats("/Buffers/color"), serial.host.readFloats("/Buffers/color"));
    EXPECT_EQ(parallel.host.readInts("/Buffers/id"), serial.host.readInts("/Buffers/id"));
    // An edit re-syncs the same prims either way.
    for (ManyPrims* scene : {&serial, &parallel}) {
        scene->host.onGetValue = nullptr;
        scene->host.setTransform("/Planes/P9", translation(0, 0, 1));
        scene->host.set("/Planes/P10", "points",
                        HostValue::points({{-0.2f, -0.2f, 0}, {0.2f, -0.2f, 0}, {0.2f, 0.2f, 0}, {-0.2f, 0.2f, 0}}));
        scene->host.api().markDirty(scene->host.delegate(), "/Planes/P9", OBSCURA_DIRTY_TRANSFORM);
        scene->host.api().markDirty(scene->host.delegate(), "/Planes/P10", OBSCURA_DIRTY_POINTS);
        ASSERT_EQ(scene->render(), OBSCURA_ERROR_BAD_PRIM_DATA) << scene->host.lastError();
    }
    EXPECT_EQ(renderStats(parallel.host).primsSynced, 2u);
    EXPECT_EQ(parallel.host.readFloats("/Buffers/color"), serial.host.readFloats("/Buffers/color"));
}

TEST(ParallelSync, AHostWithoutTheFlagIsCalledOnItsOwnThreadOnly) {
    ManyPrims scene(false);
    ASSERT_EQ(scene.render(), OBSCURA_ERROR_BAD_PRIM_DATA) << scene.host.lastError();
    EXPECT_EQ(scene.host.callbackThreads, std::set<std::thread::id>{std::this_thread::get_id()});
    EXPECT_EQ(scene.host.logThreads, std::set<std::thread::id>{std::this_thread::get_id()});
}

}  // namespace
}  // namespace obscura::test

namespace obscura::test {
namespace {

// The schemas own which dirty bit reads which attribute again (schemas/*.json): for one prim of
// every type, marking an attribute's bit makes the next render ask the host for that attribute,
// for every attribute a first sync asks for.
TEST(SchemaDirtyBits, MarkingAnAttributesBitAsksForItAgain) {
    TestHost host;
    std::map<std::string, std::string> types;  // path -> prim type
    auto add = [&](const std::string& type, const std::string& path, std::map<std::string, HostValue> values,
                   Matrix transform) {
        host.addPrim(type, path, std::move(values), transform);
        types[path] = type;
    };
    add("camera", "/Camera",
        {{"shutter:open", HostValue::doubleValue(-0.25)}, {"shutter:close", HostValue::doubleValue(0.25)}},
        translation(0, 0, 12));
    addPlane(host, "/Mesh", "/Looks/Grey", 0.5, translation(-3, 2, 0));
    types["/Mesh"] = "mesh";
    addMaterial(host, "/Looks/Grey", {0.5f, 0.5f, 0.5f});
    types["/Looks/Grey"] = "material";
    addPlane(host, "/Proto", "", 0.3, translation(0, 0, -50));
    types["/Proto"] = "mesh";
    add("instancer", "/Instancer",
        {{"prototypes", HostValue::paths({"/Proto"})},
         {"protoIndices", HostValue::intArray({0})},
         {"positions", HostValue::points({{0, 0, 50}})}},
        translation(3, 2, 0));
    const char* implicit[] = {"sphere", "cube", "cylinder", "cylinder1", "cone", "capsule", "capsule1", "plane"};
    for (size_t i = 0; i < std::size(implicit); ++i)
        add(implicit[i], std::string("/Implicit/") + implicit[i], {}, translation(double(i) - 3.5, -1, 0));
    HostValue widths = HostValue::floatValue(0.1f);
    widths.isArray = true;  // float[] of one, constant
    add("basisCurves", "/Curves",
        {{"points", HostValue::points({{0, 0, 0}, {1, 0, 0}})},
         {"curveVertexCounts", HostValue::intArray({2})},
         {"type", HostValue::token("linear")},
         {"widths", widths}},
        translation(-2, -3, 0));
    host.setInterpolation("/Curves", "widths", OBSCURA_INTERPOLATION_CONSTANT);
    add("points", "/Points", {{"points", HostValue::points({{0, 0, 0}, {0.5f, 0, 0}})}}, translation(2, -3, 0));
    for (const char* light : {"distantLight", "sphereLight", "rectLight", "diskLight", "domeLight"})
        add(light, std::string("/Lights/") + light, {}, identity());
    host.addRenderBuffer("/Buffers/color", "float32Vec4", 32, 32);
    types["/Buffers/color"] = "renderBuffer";
    auto render = [&] { return host.render("/Camera", {{"color", "/Buffers/color"}}); };
    ASSERT_EQ(render(), OBSCURA_OK) << host.lastError();
    const auto firstSync = host.valuesAskedFor;
    ASSERT_GT(firstSync.size(), 100u);
    std::set<ObscuraDirtyBits> bits;
    for (const schema::PrimSchema& prim : schema::primSchemas())
        for (const schema::AttributeSchema& a : std::span(prim.attributes, prim.attributeCount)) bits.insert(a.dirtyBit);
    for (ObscuraDirtyBits bit : bits) {
        host.resetCounters();
        for (const auto& [path, type] : types) ASSERT_EQ(host.api().markDirty(host.delegate(), path.c_str(), bit), OBSCURA_OK);
        ASSERT_EQ(render(), OBSCURA_OK) << host.lastError();
        for (const auto& [path, attribute] : firstSync)
            if (schema::attributeOf(types.at(path), attribute).dirtyBit == bit)
                EXPECT_TRUE(host.valuesAskedFor.count({path, attribute}))
                    << path << " (" << types.at(path) << ") " << attribute << ": not asked for again when bit 0x"
                    << std::hex << bit << " is marked";
    }
}

}  // namespace
}  // namespace obscura::test
