// The ABI's promises (include/obscura/obscura.h): re-entrant calls from callbacks are refused and
// change nothing, output structs keep the host's chain, a bad render buffer skips only itself, a
// size the device cannot make is refused, a mapping lasts until unmap.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

struct TwoPlanes {
    TestHost host;
    int32_t leftId = -1, rightId = -1;
    TwoPlanes() {
        host.addCamera("/Camera", translation(0, 0, 5));
        addPlane(host, "/Left", "", 1.0, translation(-1.2, 0, 0));
        addPlane(host, "/Right", "", 1.0, translation(1.2, 0, 0));
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    }
    ObscuraStatus render() { return host.render("/Camera", {{"primId", "/Buffers/id"}}); }
    int pixelsOf(const std::string& prim) {
        int32_t id = -1;
        EXPECT_EQ(host.api().getPrimId(host.delegate(), prim.c_str(), &id), OBSCURA_OK);
        int n = 0;
        for (int32_t v : host.readInts("/Buffers/id")) n += v == id;
        return n;
    }
};

TEST(Reentrancy, RemovingAPrimFromACallbackIsRefusedAndChangesNothing) {
    TwoPlanes s;
    ObscuraStatus inside = OBSCURA_OK;
    std::string message;
    s.host.onGetValue = [&](const std::string& path, const std::string&) {
        if (path != "/Left" || inside != OBSCURA_OK) return;
        inside = s.host.api().removePrim(s.host.delegate(), "/Right");
        message = s.host.api().lastError(s.host.delegate());
    };
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(inside, OBSCURA_ERROR_INVALID_STATE);
    EXPECT_NE(message.find("removePrim"), std::string::npos) << message;
    EXPECT_NE(message.find("callback"), std::string::npos) << message;
    s.host.onGetValue = nullptr;
    EXPECT_GT(s.pixelsOf("/Right"), 100) << "the refused removal must leave the prim drawn";
    EXPECT_TRUE(s.host.loggedErrors().empty()) << s.host.loggedErrors().front();
}

TEST(Reentrancy, EveryCallFromACallbackIsRefusedAndTheNextRenderIsNormal) {
    TwoPlanes s;
    std::vector<ObscuraStatus> inside;
    s.host.onGetValue = [&](const std::string& path, const std::string&) {
        if (path != "/Left" || !inside.empty()) return;
        const ObscuraApiV1& api = s.host.api();
        ObscuraDelegate d = s.host.delegate();
        inside.push_back(api.markDirty(d, "/Right", OBSCURA_DIRTY_POINTS));
        inside.push_back(api.insertPrim(d, "mesh", "/Late"));
        inside.push_back(api.setRenderSetting(d, "exposure", nullptr));
        ObscuraRenderStats stats{OBSCURA_STRUCTURE_TYPE_RENDER_STATS, nullptr, sizeof(stats)};
        inside.push_back(api.getRenderStats(d, &stats));
        ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(desc), "/Camera",
                                   {0, 0, 8, 8}, 0.0, 0, nullptr};
        inside.push_back(api.render(d, &desc));
        inside.push_back(api.destroyDelegate(d));
    };
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    ASSERT_EQ(inside.size(), 6u);
    for (size_t i = 0; i < inside.size(); ++i) EXPECT_EQ(inside[i], OBSCURA_ERROR_INVALID_STATE) << "call " << i;
    s.host.onGetValue = nullptr;
    // Nothing was half-done: no /Late prim, and /Right is clean (the refused mark left no bit that a
    // later render would pull).
    EXPECT_EQ(s.host.api().removePrim(s.host.delegate(), "/Late"), OBSCURA_ERROR_NOT_FOUND);
    s.host.resetCounters();
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(s.host.getValueCalls["/Right"], 0);
    // A mark made outside the callback is honoured.
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Right", OBSCURA_DIRTY_POINTS), OBSCURA_OK);
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_GT(s.host.getValueCalls["/Right"], 0);
}

TEST(OutputStructs, RenderStatsKeepTheHostsChainAndFillMemoryStats) {
    TwoPlanes s;
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    ObscuraMemoryStats memory{OBSCURA_STRUCTURE_TYPE_MEMORY_STATS, nullptr, sizeof(memory)};
    ObscuraRenderStats stats{OBSCURA_STRUCTURE_TYPE_RENDER_STATS, &memory, sizeof(stats) + 16};
    ASSERT_EQ(s.host.api().getRenderStats(s.host.delegate(), &stats), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(stats.pNext, &memory);
    EXPECT_EQ(stats.structSize, sizeof(stats) + 16);
    EXPECT_EQ(stats.sType, OBSCURA_STRUCTURE_TYPE_RENDER_STATS);
    EXPECT_GT(stats.trianglesDrawn, 0u);
    EXPECT_EQ(memory.pNext, nullptr);
    EXPECT_EQ(memory.structSize, sizeof(memory));
    EXPECT_GT(memory.deviceMemoryBlocks, 0u);
    EXPECT_GT(memory.deviceMemoryInUse, 0u);
    EXPECT_LE(memory.deviceMemoryInUse, memory.deviceMemoryReserved);
}

TEST(BadRenderBuffer, OnlyTheBadBufferIsSkipped) {
    TwoPlanes s;
    s.host.expectError("skipped prim /Buffers/badDepth: dimensions");
    s.host.addPrim("renderBuffer", "/Buffers/badDepth",
                   {{"dimensions", HostValue::float2(64.0f, 64.0f)}, {"format", HostValue::token("float32")}});
    ASSERT_EQ(s.host.render("/Camera", {{"primId", "/Buffers/id"}, {"depth", "/Buffers/badDepth"}}),
              OBSCURA_ERROR_BAD_PRIM_DATA);
    EXPECT_NE(s.host.lastError().find("/Buffers/badDepth"), std::string::npos) << s.host.lastError();
    EXPECT_GT(s.pixelsOf("/Left"), 100) << "the good buffer holds this frame";
    ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
    EXPECT_EQ(s.host.api().mapRenderBuffer(s.host.delegate(), "/Buffers/badDepth", &m), OBSCURA_ERROR_INVALID_STATE);
}

TEST(BadRenderBuffer, SizesTheDeviceCannotMakeAreRefusedClearly) {
    TwoPlanes s;
    ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(desc), "/Camera",
                               {0, 0, 100000, 1}, 0.0, 0, nullptr};
    EXPECT_EQ(s.host.api().render(s.host.delegate(), &desc), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(s.host.lastError().find("100000x1"), std::string::npos) << s.host.lastError();
    EXPECT_NE(s.host.lastError().find("largest image"), std::string::npos) << s.host.lastError();
    s.host.expectError("skipped prim /Buffers/wide: dimensions (100000, 1)");
    s.host.addRenderBuffer("/Buffers/wide", "int32", 100000, 1);
    EXPECT_EQ(s.host.render("/Camera", {{"primId", "/Buffers/wide"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
    EXPECT_NE(s.host.lastError().find("/Buffers/wide"), std::string::npos) << s.host.lastError();
}

TEST(Mapping, APointerStaysValidAndUnchangedUntilUnmap) {
    TwoPlanes s;
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    const ObscuraApiV1& api = s.host.api();
    ObscuraDelegate d = s.host.delegate();
    ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
    ASSERT_EQ(api.mapRenderBuffer(d, "/Buffers/id", &m), OBSCURA_OK);
    EXPECT_EQ(m.sType, OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER);
    EXPECT_EQ(m.structSize, sizeof(m));
    const auto* ids = static_cast<const int32_t*>(m.data);
    std::vector<int32_t> before(ids, ids + size_t(m.width) * m.height);
    // Render refuses to write a mapped buffer, and the mapping's contents stay the frame they were.
    s.host.setTransform("/Left", translation(-3.0, 0, 0));
    ASSERT_EQ(api.markDirty(d, "/Left", OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    EXPECT_EQ(s.render(), OBSCURA_ERROR_INVALID_STATE);
    EXPECT_NE(s.host.lastError().find("mapped"), std::string::npos) << s.host.lastError();
    EXPECT_EQ(std::vector<int32_t>(ids, ids + before.size()), before);
    ObscuraMappedBuffer again{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(again)};
    ASSERT_EQ(api.mapRenderBuffer(d, "/Buffers/id", &again), OBSCURA_OK);
    EXPECT_EQ(again.data, m.data);
    EXPECT_EQ(api.unmapRenderBuffer(d, "/Buffers/id"), OBSCURA_OK);
    EXPECT_EQ(api.unmapRenderBuffer(d, "/Buffers/id"), OBSCURA_OK) << "unmapping an unmapped buffer";
    EXPECT_EQ(api.unmapRenderBuffer(d, "/Buffers/none"), OBSCURA_ERROR_NOT_FOUND);
    // After unmap the next render writes the buffer, the edit included.
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_NE(s.host.readInts("/Buffers/id"), before);
}

}  // namespace
}  // namespace obscura::test
