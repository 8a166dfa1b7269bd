// The ABI's promises (include/obscura/obscura.h): re-entrant calls from callbacks are refused and
// change nothing, output structs keep the host's chain, a bad render buffer skips only itself, a
// size the device cannot make is refused, a mapping lasts until unmap; then every entry point's
// status codes, NULL handling, struct checks and lastError.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

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

// ABI 1.3 says what the memory in use holds: the parts are within it and each owner's is there.
TEST(OutputStructs, MemoryStatsSayWhatTheMemoryHolds) {
    TwoPlanes s;
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    ObscuraMemoryStats memory{};
    memory.sType = OBSCURA_STRUCTURE_TYPE_MEMORY_STATS;
    memory.structSize = sizeof(memory);
    ObscuraRenderStats stats{OBSCURA_STRUCTURE_TYPE_RENDER_STATS, &memory, sizeof(stats)};
    ASSERT_EQ(s.host.api().getRenderStats(s.host.delegate(), &stats), OBSCURA_OK) << s.host.lastError();
    const uint64_t parts = memory.frameTargetBytes + memory.frameHistoryBytes + memory.textureBytes +
                           memory.geometryBytes + memory.renderBufferBytes;
    EXPECT_LE(parts, memory.deviceMemoryInUse);
    EXPECT_LE(memory.imageBytes, memory.deviceMemoryInUse);
    // The G-buffer alone: a depth/stencil and three colour targets of 4 bytes a pixel at least.
    EXPECT_GE(memory.frameTargetBytes, uint64_t(kWidth) * kHeight * 4 * 4);
    EXPECT_LE(memory.frameTargetBytes, memory.imageBytes);
    EXPECT_GE(memory.renderBufferBytes, uint64_t(kWidth) * kHeight * sizeof(int32_t));
    // Two quads (one shared copy): positions of four corners and two triangles' indices at least.
    EXPECT_GE(memory.geometryBytes, 4 * 3 * sizeof(float) + 6 * sizeof(uint32_t));
    EXPECT_EQ(memory.textureBytes, 0u);  // no material textures in this scene

    // A host built against ABI 1.1 passes the smaller struct: the first counters, nothing past them.
    ObscuraMemoryStats old;
    std::memset(&old, 0xab, sizeof(old));
    old.sType = OBSCURA_STRUCTURE_TYPE_MEMORY_STATS;
    old.pNext = nullptr;
    old.structSize = offsetof(ObscuraMemoryStats, imageBytes);
    stats.pNext = &old;
    ASSERT_EQ(s.host.api().getRenderStats(s.host.delegate(), &stats), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(old.deviceMemoryInUse, memory.deviceMemoryInUse);
    const auto* past = reinterpret_cast<const unsigned char*>(&old) + offsetof(ObscuraMemoryStats, imageBytes);
    for (size_t i = 0; i < sizeof(ObscuraMemoryStats) - offsetof(ObscuraMemoryStats, imageBytes); ++i)
        ASSERT_EQ(past[i], 0xab) << "byte " << i << " past the 1.1 struct was written";
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

// The header's promises entry point by entry point (include/obscura/obscura.h).
namespace obscura::test {
namespace {

ObscuraRenderPassDesc passDesc(const char* camera, const ObscuraAovBinding* bindings, uint32_t count) {
    return {OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(ObscuraRenderPassDesc), camera, {0, 0, 0, 0}, 0.0,
            count, bindings};
}

TEST(Contract, ANullDelegateOrRequiredPointerIsAnInvalidArgumentAndChangesNothing) {
    TwoPlanes s;
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    const ObscuraApiV1& api = s.host.api();
    ObscuraDelegate d = s.host.delegate();
    const ObscuraSceneDelegate& scene = s.host.sceneDelegate();
    ObscuraAovBinding binding{"primId", "/Buffers/id"};
    ObscuraRenderPassDesc desc = passDesc("/Camera", &binding, 1);
    ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
    ObscuraRenderStats stats{OBSCURA_STRUCTURE_TYPE_RENDER_STATS, nullptr, sizeof(stats)};
    uint32_t count = 0;
    int32_t id = 0;
    auto refused = [&](ObscuraStatus status, const char* call) {
        EXPECT_EQ(status, OBSCURA_ERROR_INVALID_ARGUMENT) << call;
        EXPECT_STRNE(api.lastError(nullptr), "") << call << ": the message of a call without a delegate";
    };
    refused(api.setSceneDelegate(nullptr, &scene), "setSceneDelegate");
    refused(api.insertPrim(nullptr, "mesh", "/M"), "insertPrim");
    refused(api.removePrim(nullptr, "/Left"), "removePrim");
    refused(api.markDirty(nullptr, "/Left", OBSCURA_DIRTY_ALL), "markDirty");
    refused(api.setRenderSetting(nullptr, "exposure", nullptr), "setRenderSetting");
    refused(api.render(nullptr, &desc), "render");
    refused(api.mapRenderBuffer(nullptr, "/Buffers/id", &mapped), "mapRenderBuffer");
    refused(api.unmapRenderBuffer(nullptr, "/Buffers/id"), "unmapRenderBuffer");
    refused(api.getPassTimings(nullptr, nullptr, &count), "getPassTimings");
    refused(api.getRenderStats(nullptr, &stats), "getRenderStats");
    refused(api.getPrimId(nullptr, "/Left", &id), "getPrimId");
    refused(api.createDelegate(nullptr, nullptr), "createDelegate without outDelegate");
    refused(api.enumerateDevices(nullptr, nullptr), "enumerateDevices without count");
    auto refusedOn = [&](ObscuraStatus status, const char* call) {
        EXPECT_EQ(status, OBSCURA_ERROR_INVALID_ARGUMENT) << call;
        EXPECT_STRNE(api.lastError(d), "") << call;
    };
    refusedOn(api.setSceneDelegate(d, nullptr), "setSceneDelegate without a scene delegate");
    refusedOn(api.insertPrim(d, "mesh", nullptr), "insertPrim without a path");
    refusedOn(api.removePrim(d, nullptr), "removePrim without a path");
    refusedOn(api.markDirty(d, nullptr, OBSCURA_DIRTY_ALL), "markDirty without a path");
    refusedOn(api.setRenderSetting(d, nullptr, nullptr), "setRenderSetting without a key");
    refusedOn(api.render(d, nullptr), "render without a description");
    refusedOn(api.mapRenderBuffer(d, nullptr, &mapped), "mapRenderBuffer without a path");
    refusedOn(api.mapRenderBuffer(d, "/Buffers/id", nullptr), "mapRenderBuffer without a struct");
    refusedOn(api.unmapRenderBuffer(d, nullptr), "unmapRenderBuffer without a path");
    refusedOn(api.getPassTimings(d, nullptr, nullptr), "getPassTimings without count");
    refusedOn(api.getRenderStats(d, nullptr), "getRenderStats without a struct");
    refusedOn(api.getPrimId(d, nullptr, &id), "getPrimId without a path");
    refusedOn(api.getPrimId(d, "/Left", nullptr), "getPrimId without outId");
    // Nothing changed: nothing is dirty, both planes still draw, nothing is mapped.
    s.host.resetCounters();
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_TRUE(s.host.getValueCalls.empty());
    EXPECT_GT(s.pixelsOf("/Left"), 100);
    EXPECT_GT(s.pixelsOf("/Right"), 100);
}

TEST(Contract, StructsOfAnotherTypeOrTooSmallAreInvalidArguments) {
    TwoPlanes s;
    const ObscuraApiV1& api = s.host.api();
    ObscuraDelegate d = s.host.delegate();
    ObscuraDelegateCreateInfo info{OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE, nullptr, sizeof(info), nullptr, 1, nullptr,
                                   nullptr};
    ObscuraDelegate created = d;  // a failed creation writes NULL
    EXPECT_EQ(api.createDelegate(&info, &created), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(created, nullptr);
    info = {OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO, nullptr, sizeof(info) - 8, nullptr, 1, nullptr, nullptr};
    EXPECT_EQ(api.createDelegate(&info, &created), OBSCURA_ERROR_INVALID_ARGUMENT);
    ObscuraSceneDelegate scene = s.host.sceneDelegate();
    scene.sType = OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC;
    EXPECT_EQ(api.setSceneDelegate(d, &scene), OBSCURA_ERROR_INVALID_ARGUMENT);
    scene = s.host.sceneDelegate();
    scene.structSize -= 8;
    EXPECT_EQ(api.setSceneDelegate(d, &scene), OBSCURA_ERROR_INVALID_ARGUMENT);
    scene = s.host.sceneDelegate();
    scene.getValue = nullptr;
    EXPECT_EQ(api.setSceneDelegate(d, &scene), OBSCURA_ERROR_INVALID_ARGUMENT);
    ObscuraAovBinding binding{"primId", "/Buffers/id"};
    ObscuraRenderPassDesc desc = passDesc("/Camera", &binding, 1);
    desc.sType = OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER;
    EXPECT_EQ(api.render(d, &desc), OBSCURA_ERROR_INVALID_ARGUMENT);
    desc = passDesc("/Camera", &binding, 1);
    desc.structSize -= 8;
    EXPECT_EQ(api.render(d, &desc), OBSCURA_ERROR_INVALID_ARGUMENT);
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError() << ": the refused scene delegates changed nothing";
    ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped) - 8};
    EXPECT_EQ(api.mapRenderBuffer(d, "/Buffers/id", &mapped), OBSCURA_ERROR_INVALID_ARGUMENT);
    ObscuraRenderStats stats{OBSCURA_STRUCTURE_TYPE_RENDER_STATS, nullptr, sizeof(stats) - 8};
    EXPECT_EQ(api.getRenderStats(d, &stats), OBSCURA_ERROR_INVALID_ARGUMENT);
}

TEST(Contract, LastErrorIsNeverNullKeepsTheLastFailureAndIsPerDelegateAndPerThread) {
    TwoPlanes first, second;
    const ObscuraApiV1& api = first.host.api();
    ObscuraDelegate d = first.host.delegate();
    ASSERT_NE(api.lastError(d), nullptr);
    EXPECT_STREQ(api.lastError(d), "");
    EXPECT_EQ(api.removePrim(d, "/Nowhere"), OBSCURA_ERROR_NOT_FOUND);
    const std::string message = api.lastError(d);
    EXPECT_NE(message.find("/Nowhere"), std::string::npos) << message;
    ASSERT_EQ(first.render(), OBSCURA_OK);
    EXPECT_EQ(api.lastError(d), message) << "a successful call leaves the last message in place";
    EXPECT_STREQ(api.lastError(second.host.delegate()), "") << "messages are per delegate";
    // Calls without a delegate: the message is this thread's.
    EXPECT_EQ(api.createDelegate(nullptr, nullptr), OBSCURA_ERROR_INVALID_ARGUMENT);
    const std::string here = api.lastError(nullptr);
    EXPECT_NE(here.find("outDelegate"), std::string::npos) << here;
    std::string there;
    std::thread([&] { there = api.lastError(nullptr); }).join();
    EXPECT_EQ(there, "");
}

TEST(Contract, ACallFromAnotherThreadDuringACallIsRefusedWithItsMessageOnThatThread) {
    TwoPlanes s;
    const ObscuraApiV1& api = s.host.api();
    ObscuraDelegate d = s.host.delegate();
    ObscuraStatus marked = OBSCURA_OK, destroyed = OBSCURA_OK;
    std::string message;
    s.host.onGetValue = [&](const std::string& path, const std::string&) {
        if (path != "/Left" || marked != OBSCURA_OK) return;
        std::thread([&] {
            marked = api.markDirty(d, "/Right", OBSCURA_DIRTY_POINTS);
            message = api.lastError(nullptr);
            destroyed = api.destroyDelegate(d);
        }).join();
    };
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(marked, OBSCURA_ERROR_INVALID_STATE);
    EXPECT_EQ(destroyed, OBSCURA_ERROR_INVALID_STATE);
    EXPECT_NE(message.find("another thread"), std::string::npos) << message;
    EXPECT_STREQ(api.lastError(d), "") << "the running call's message is untouched";
    s.host.onGetValue = nullptr;
    s.host.resetCounters();
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(s.host.getValueCalls.count("/Right"), 0u) << "the refused mark left no bit";
}

TEST(Contract, QueriesBeforeAnyRenderAndOfPrimsThatDrawNothing) {
    TwoPlanes s;
    const ObscuraApiV1& api = s.host.api();
    ObscuraDelegate d = s.host.delegate();
    uint32_t count = 7;
    EXPECT_EQ(api.getPassTimings(d, nullptr, &count), OBSCURA_OK);
    EXPECT_EQ(count, 0u) << "no timings before the first render";
    ObscuraRenderStats stats{OBSCURA_STRUCTURE_TYPE_RENDER_STATS, nullptr, sizeof(stats)};
    ASSERT_EQ(api.getRenderStats(d, &stats), OBSCURA_OK);
    EXPECT_EQ(stats.primsSynced, 0u);
    EXPECT_EQ(stats.trianglesDrawn, 0u);
    int32_t id = 5;
    EXPECT_EQ(api.getPrimId(d, "/Camera", &id), OBSCURA_ERROR_NOT_FOUND) << "a camera draws nothing";
    EXPECT_EQ(api.getPrimId(d, "/Buffers/id", &id), OBSCURA_ERROR_NOT_FOUND) << "a render buffer draws nothing";
    EXPECT_EQ(api.getPrimId(d, "/Nowhere", &id), OBSCURA_ERROR_NOT_FOUND);
    ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
    EXPECT_EQ(api.mapRenderBuffer(d, "/Buffers/id", &mapped), OBSCURA_ERROR_INVALID_STATE) << "never rendered";
    EXPECT_EQ(api.mapRenderBuffer(d, "/Left", &mapped), OBSCURA_ERROR_NOT_FOUND) << "not a render buffer";
    EXPECT_EQ(api.unmapRenderBuffer(d, "/Left"), OBSCURA_ERROR_NOT_FOUND) << "not a render buffer";
    // After a render: a count, then at most that many entries, each written whole.
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    ASSERT_EQ(api.getPassTimings(d, nullptr, &count), OBSCURA_OK);
    ASSERT_GT(count, 1u);
    std::vector<ObscuraPassTiming> timings(count);
    uint32_t one = 1;
    ASSERT_EQ(api.getPassTimings(d, timings.data(), &one), OBSCURA_OK);
    EXPECT_EQ(one, 1u);
    EXPECT_EQ(timings[0].sType, OBSCURA_STRUCTURE_TYPE_PASS_TIMING);
    EXPECT_EQ(timings[0].structSize, sizeof(ObscuraPassTiming));
    EXPECT_EQ(timings[0].pNext, nullptr);
    EXPECT_STRNE(timings[0].pass, "");
    EXPECT_EQ(timings[1].structSize, 0u) << "entries past *count are not written";
    // Render settings are described without a delegate; either out pointer may be NULL.
    uint32_t settings = 0;
    const char* name = nullptr;
    while (api.describeRenderSetting(settings, &name, nullptr) == OBSCURA_OK) ++settings;
    EXPECT_GT(settings, 10u);
    EXPECT_EQ(api.describeRenderSetting(settings, nullptr, nullptr), OBSCURA_ERROR_NOT_FOUND);
    EXPECT_EQ(api.describeRenderSetting(0, nullptr, nullptr), OBSCURA_OK);
    // Devices: a count, then at most that many, each written whole.
    uint32_t devices = 0;
    ASSERT_EQ(api.enumerateDevices(nullptr, &devices), OBSCURA_OK);
    ASSERT_GE(devices, 1u);
    std::vector<ObscuraDeviceInfo> infos(devices + 1);
    uint32_t asked = devices + 1;
    ASSERT_EQ(api.enumerateDevices(infos.data(), &asked), OBSCURA_OK);
    EXPECT_EQ(asked, devices);
    EXPECT_EQ(infos[0].sType, OBSCURA_STRUCTURE_TYPE_DEVICE_INFO);
    EXPECT_EQ(infos[0].structSize, sizeof(ObscuraDeviceInfo));
    EXPECT_STRNE(infos[0].name, "");
}

TEST(Contract, ANewSceneDelegateMakesEveryPrimDirtyAndARefusedInsertKeepsThePrim) {
    TwoPlanes s;
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    const int32_t left = [&] {
        int32_t id = -1;
        EXPECT_EQ(s.host.api().getPrimId(s.host.delegate(), "/Left", &id), OBSCURA_OK);
        return id;
    }();
    EXPECT_EQ(s.host.api().insertPrim(s.host.delegate(), "camera", "/Left"), OBSCURA_ERROR_ALREADY_EXISTS);
    ASSERT_EQ(s.host.api().setSceneDelegate(s.host.delegate(), &s.host.sceneDelegate()), OBSCURA_OK);
    s.host.resetCounters();
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(renderStats(s.host).primsSynced, 4u) << "camera, two planes and the render buffer";
    int32_t after = -1;
    EXPECT_EQ(s.host.api().getPrimId(s.host.delegate(), "/Left", &after), OBSCURA_OK);
    EXPECT_EQ(after, left) << "the refused insert left the mesh and its id";
    EXPECT_GT(s.pixelsOf("/Left"), 100);
    // markDirty with no bits marks nothing.
    s.host.resetCounters();
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Left", OBSCURA_DIRTY_CLEAN), OBSCURA_OK);
    ASSERT_EQ(s.render(), OBSCURA_OK);
    EXPECT_EQ(renderStats(s.host).primsSynced, 0u);
}

TEST(Mapping, AMappedBufferOutsideTheRenderStaysAsItWasEvenResizedUntilUnmap) {
    TwoPlanes s;
    s.host.addRenderBuffer("/Buffers/other", "int32", kWidth, kHeight);
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    const ObscuraApiV1& api = s.host.api();
    ObscuraDelegate d = s.host.delegate();
    ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
    ASSERT_EQ(api.mapRenderBuffer(d, "/Buffers/id", &m), OBSCURA_OK);
    const auto* ids = static_cast<const int32_t*>(m.data);
    const std::vector<int32_t> before(ids, ids + size_t(m.width) * m.height);
    // Another buffer renders an edited scene; then the mapped one is given a new size and the
    // other renders again: the mapping neither moves nor changes.
    s.host.setTransform("/Left", translation(-3.0, 0, 0));
    ASSERT_EQ(api.markDirty(d, "/Left", OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    ASSERT_EQ(s.host.render("/Camera", {{"primId", "/Buffers/other"}}), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(std::vector<int32_t>(ids, ids + before.size()), before);
    s.host.set("/Buffers/id", "dimensions", HostValue::int2(kWidth / 2, kHeight / 2));
    ASSERT_EQ(api.markDirty(d, "/Buffers/id", OBSCURA_DIRTY_PARAMS), OBSCURA_OK);
    ASSERT_EQ(s.host.render("/Camera", {{"primId", "/Buffers/other"}}), OBSCURA_OK) << s.host.lastError();
    EXPECT_EQ(std::vector<int32_t>(ids, ids + before.size()), before);
    ObscuraMappedBuffer again{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(again)};
    EXPECT_EQ(api.mapRenderBuffer(d, "/Buffers/id", &again), OBSCURA_ERROR_INVALID_STATE) << "resized, not rendered";
    // The new size takes effect at its first render after unmap.
    ASSERT_EQ(api.unmapRenderBuffer(d, "/Buffers/id"), OBSCURA_OK);
    ASSERT_EQ(s.render(), OBSCURA_OK) << s.host.lastError();
    ASSERT_EQ(api.mapRenderBuffer(d, "/Buffers/id", &again), OBSCURA_OK);
    EXPECT_EQ(again.width, uint32_t(kWidth / 2));
    EXPECT_EQ(again.height, uint32_t(kHeight / 2));
    // Removing a mapped buffer ends its mapping with it; destroying the delegate ends the rest.
    ASSERT_EQ(api.mapRenderBuffer(d, "/Buffers/other", &m), OBSCURA_OK);
    ASSERT_EQ(api.removePrim(d, "/Buffers/id"), OBSCURA_OK);
    EXPECT_EQ(api.unmapRenderBuffer(d, "/Buffers/id"), OBSCURA_ERROR_NOT_FOUND);
    EXPECT_EQ(s.host.destroyDelegate(), OBSCURA_OK);
}

}  // namespace
}  // namespace obscura::test
