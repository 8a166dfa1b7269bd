// Incremental sync: a render pulls only what the dirty bits name (callbacks counted per prim).
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <thread>

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
    uint32_t synced() {
        ObscuraRenderStats s{};
        s.structSize = sizeof(s);
        host.api().getRenderStats(host.delegate(), &s);
        return s.primsSynced;
    }
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
