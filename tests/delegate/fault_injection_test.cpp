// Device loss and out-of-memory, simulated through OBSCURA_FAULT_INJECTION: render
// returns the status with a message, the delegate is destroyed cleanly afterwards (the validation
// layer reports every Vulkan object left alive at device destruction as an error) and a new one
// renders.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

namespace obscura::test {
namespace {

// A delegate created while OBSCURA_FAULT_INJECTION says `fault`.
std::unique_ptr<LitPlaneScene> sceneWithFault(const char* fault) {
    setenv("OBSCURA_FAULT_INJECTION", fault, 1);
    auto scene = std::make_unique<LitPlaneScene>();
    unsetenv("OBSCURA_FAULT_INJECTION");
    scene->host.addPrim("distantLight", "/Sun", {{"inputs:intensity", HostValue::floatValue(1.0f)}},
                        lightPointingAlong({0.0, 0.0, -1.0}));
    return scene;
}

ObscuraStatus renderColor(LitPlaneScene& scene) {
    return scene.host.render("/Camera", {{"color", "/Buffers/color"}});
}

void expectCleanDestructionAndAFreshDelegate(LitPlaneScene& scene) {
    EXPECT_EQ(scene.host.destroyDelegate(), OBSCURA_OK);
    EXPECT_TRUE(scene.host.loggedErrors().empty()) << scene.host.loggedErrors().front();
    LitPlaneScene fresh;
    std::vector<float> color = fresh.renderColor();
    EXPECT_GT(color[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 4 + 3], 0.99f) << "the plane covers the centre";
}

TEST(FaultInjection, ALostDeviceFailsRenderFromThenOnAndTheDelegateStillDestroysCleanly) {
    auto scene = sceneWithFault("device-lost:2");
    ASSERT_EQ(renderColor(*scene), OBSCURA_OK) << scene->host.lastError();
    EXPECT_EQ(renderColor(*scene), OBSCURA_ERROR_DEVICE);
    EXPECT_NE(scene->host.lastError().find("VK_ERROR_DEVICE_LOST"), std::string::npos) << scene->host.lastError();
    EXPECT_EQ(renderColor(*scene), OBSCURA_ERROR_DEVICE) << "a lost device stays lost";
    EXPECT_NE(scene->host.lastError().find("create a new one"), std::string::npos) << scene->host.lastError();
    expectCleanDestructionAndAFreshDelegate(*scene);
}

TEST(FaultInjection, AFailedAllocationFailsThatRenderOnlyAndLeaksNothing) {
    auto scene = sceneWithFault("out-of-memory:2");
    ASSERT_EQ(renderColor(*scene), OBSCURA_OK) << scene->host.lastError();
    std::vector<float> first = scene->host.readFloats("/Buffers/color");
    scene->host.set("/Looks/Grey", "inputs:diffuseColor", HostValue::float3(0.2f, 0.2f, 0.2f));
    ASSERT_EQ(scene->host.api().markDirty(scene->host.delegate(), "/Looks/Grey", OBSCURA_DIRTY_PARAMS), OBSCURA_OK);
    EXPECT_EQ(renderColor(*scene), OBSCURA_ERROR_OUT_OF_MEMORY);
    EXPECT_NE(scene->host.lastError().find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos)
        << scene->host.lastError();
    // Memory is back: the next render succeeds, with the edit the failed one could not show.
    ASSERT_EQ(renderColor(*scene), OBSCURA_OK) << scene->host.lastError();
    std::vector<float> after = scene->host.readFloats("/Buffers/color");
    size_t centre = (size_t(kHeight / 2) * kWidth + kWidth / 2) * 4;
    EXPECT_LT(after[centre], 0.6f * first[centre]) << "the darker material of the failed render's edit";
    expectCleanDestructionAndAFreshDelegate(*scene);
}

TEST(FaultInjection, AnUnknownFaultIsReportedAndIgnored) {
    auto scene = sceneWithFault("meteor:1");
    EXPECT_EQ(renderColor(*scene), OBSCURA_OK) << scene->host.lastError();
    bool warned = false;
    for (const auto& w : scene->host.loggedWarnings()) warned |= w.find("meteor:1") != std::string::npos;
    EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace obscura::test
