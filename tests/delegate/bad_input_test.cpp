// Bad data from a host is reported and the offending prim skipped; the rest still renders, and
// no call crashes.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <limits>

namespace obscura::test {
namespace {

struct Scene {
    TestHost host;
    int32_t goodId = -1;
    Scene() {
        host.addCamera("/Camera", translation(0, 0, 5));
        addPlane(host, "/Good", "", 1.0, translation(-1.2, 0, 0));
        addPlane(host, "/Bad", "", 1.0, translation(1.2, 0, 0));
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    }
    // Renders, expects BAD_PRIM_DATA with the bad prim named, and the good prim still drawn.
    void expectBadPrimSkipped(const std::string& why) {
        host.expectError("skipped prim /Bad: ");
        ASSERT_EQ(host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_ERROR_BAD_PRIM_DATA) << why;
        EXPECT_NE(host.lastError().find("/Bad"), std::string::npos) << host.lastError();
        ASSERT_FALSE(host.loggedErrors().empty());
        EXPECT_NE(host.loggedErrors().back().find(why), std::string::npos) << host.loggedErrors().back();
        host.api().getPrimId(host.delegate(), "/Good", &goodId);
        int32_t badId = -1;
        host.api().getPrimId(host.delegate(), "/Bad", &badId);
        int good = 0;
        for (int32_t v : host.readInts("/Buffers/id")) {
            EXPECT_NE(v, badId);
            good += v == goodId;
        }
        EXPECT_GT(good, 100);
    }
};

TEST(BadInput, NaNPointsSkipThePrim) {
    Scene s;
    float nan = std::numeric_limits<float>::quiet_NaN();
    s.host.set("/Bad", "points", HostValue::points({{-1, -1, 0}, {1, -1, 0}, {1, nan, 0}, {-1, 1, 0}}));
    s.expectBadPrimSkipped("NaN");
}

TEST(BadInput, OutOfRangeIndicesSkipThePrim) {
    Scene s;
    s.host.set("/Bad", "faceVertexIndices", HostValue::intArray({0, 1, 2, 7}));
    s.expectBadPrimSkipped("outside the 4 points");
}

TEST(BadInput, CountsThatDoNotSumSkipThePrim) {
    Scene s;
    s.host.set("/Bad", "faceVertexCounts", HostValue::intArray({3, 3}));
    s.expectBadPrimSkipped("sum to 6");
}

TEST(BadInput, WrongTypeSkipsThePrim) {
    Scene s;
    s.host.set("/Bad", "points", HostValue::token("not points"));
    s.expectBadPrimSkipped("points");
}

TEST(BadInput, FixedDataRendersAgain) {
    Scene s;
    s.host.set("/Bad", "faceVertexIndices", HostValue::intArray({0, 1, 2, 9}));
    s.expectBadPrimSkipped("outside");
    s.host.set("/Bad", "faceVertexIndices", HostValue::intArray({0, 1, 2, 3}));
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Bad", OBSCURA_DIRTY_TOPOLOGY), OBSCURA_OK);
    EXPECT_EQ(s.host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << s.host.lastError();
}

TEST(BadInput, WrongPrimvarCountIsDroppedWithAWarning) {
    Scene s;
    s.host.set("/Good", "primvars:displayColor", HostValue::points({{1, 0, 0}, {0, 1, 0}}));  // vertex needs 4
    EXPECT_EQ(s.host.render("/Camera", {{"primId", "/Buffers/id"}}), OBSCURA_OK) << s.host.lastError();
}

TEST(BadInput, ApiMisuseIsRefusedWithAMessage) {
    TestHost host;
    const auto& api = host.api();
    ObscuraDelegate d = host.delegate();
    EXPECT_EQ(api.insertPrim(d, "teapot", "/T"), OBSCURA_ERROR_UNKNOWN_TYPE);
    EXPECT_NE(std::string(api.lastError(d)).find("teapot"), std::string::npos);
    EXPECT_EQ(api.insertPrim(d, "mesh", "relative/path"), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(api.insertPrim(d, nullptr, "/X"), OBSCURA_ERROR_INVALID_ARGUMENT);
    host.addCamera("/Camera", translation(0, 0, 5));
    EXPECT_EQ(api.insertPrim(d, "camera", "/Camera"), OBSCURA_ERROR_ALREADY_EXISTS);
    EXPECT_EQ(api.markDirty(d, "/Nothing", OBSCURA_DIRTY_ALL), OBSCURA_ERROR_NOT_FOUND);
    EXPECT_EQ(api.render(d, nullptr), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(host.render("/NoSuchCamera", {}), OBSCURA_ERROR_NOT_FOUND);
    host.addRenderBuffer("/Buffers/c", "float32Vec4", 8, 8);
    EXPECT_EQ(host.render("/Camera", {{"primId", "/Buffers/c"}}), OBSCURA_ERROR_INVALID_ARGUMENT)
        << "format mismatch";
    EXPECT_EQ(host.render("/Camera", {{"beauty", "/Buffers/c"}}), OBSCURA_ERROR_NOT_FOUND);
    ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
    EXPECT_EQ(api.mapRenderBuffer(d, "/Buffers/c", &m), OBSCURA_ERROR_INVALID_STATE) << "never rendered";
    EXPECT_EQ(api.setRenderSetting(d, "noSuchSetting", nullptr), OBSCURA_ERROR_NOT_FOUND);
    const char* token = "bright";
    ObscuraValue v{OBSCURA_VALUE_TOKEN, 0, 1, &token};
    EXPECT_EQ(api.setRenderSetting(d, "exposure", &v), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(api.destroyDelegate(nullptr), OBSCURA_OK);
    EXPECT_EQ(api.insertPrim(nullptr, "mesh", "/M"), OBSCURA_ERROR_INVALID_ARGUMENT);
}

TEST(BadInput, BadRenderBufferAndCameraAreReported) {
    TestHost host;
    host.expectError("skipped prim /Camera: focalLength");
    host.expectError("skipped prim /Buffers/c: dimensions (0, 8)");
    host.addPrim("camera", "/Camera", {{"focalLength", HostValue::floatValue(-5.0f)}}, translation(0, 0, 5));
    host.addRenderBuffer("/Buffers/c", "float32Vec4", 0, 8);
    EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/c"}}), OBSCURA_ERROR_BAD_PRIM_DATA);
    EXPECT_NE(host.lastError().find("focalLength"), std::string::npos) << host.lastError();
}

}  // namespace
}  // namespace obscura::test
