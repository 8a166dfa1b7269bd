// Occlusion culling (seed 004 "Occlusion culling", render setting occlusionCulling), both routes
// (occlusionCulling:route): what the last frame's coverage buffer hides, or what this frame's early
// depth hides on the GPU, is not drawn by the camera, and nothing the camera sees is ever culled:
// every frame of a camera path renders the same image with culling as without, pixel for pixel,
// while the culled counts say the test had something to hide.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace obscura::test {
namespace {

constexpr int kCrowdInFront = 3;  // crates between the camera and the wall
constexpr int kCrowdBehind = 6;   // crates behind the wall

// A frame's colour and primId AOVs (buffers /Buffers/color and /Buffers/id) and its culling stats.
struct CulledFrame {
    std::vector<float> color;
    std::vector<int32_t> ids;
    ObscuraCullingStats culling{};
};

CulledFrame renderCulledFrame(TestHost& host, const std::string& camera) {
    CulledFrame frame;
    EXPECT_EQ(host.render(camera, {{"color", "/Buffers/color"}, {"primId", "/Buffers/id"}}), OBSCURA_OK)
        << host.lastError();
    frame.color = host.readFloats("/Buffers/color");
    frame.ids = host.readInts("/Buffers/id");
    frame.culling.sType = OBSCURA_STRUCTURE_TYPE_CULLING_STATS;
    frame.culling.structSize = sizeof(frame.culling);
    ObscuraRenderStats stats{};
    stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
    stats.structSize = sizeof(stats);
    stats.pNext = &frame.culling;
    EXPECT_EQ(host.api().getRenderStats(host.delegate(), &stats), OBSCURA_OK);
    return frame;
}

// A wall filling the view of a camera at the origin looking along +Y, a box, a glass pane and
// crates in front of it and a box, a glass box and crates behind it, lit by a shadowing sun.
// Culling on or off as asked, by the route named.
constexpr const char* kCoverageBuffer = "coverageBuffer";
constexpr const char* kGpu = "gpu";
struct WalledScene {
    TestHost host;
    explicit WalledScene(bool culling, const char* route = kCoverageBuffer, int width = kWidth, int height = kHeight) {
        setBool(host, "occlusionCulling", culling);
        setToken(host, "occlusionCulling:route", route);
        addMaterial(host, "/Looks/Grey", {0.5f, 0.5f, 0.5f}, 0.6f);
        addMaterial(host, "/Looks/Red", {0.8f, 0.1f, 0.1f}, 0.4f);
        addMaterial(host, "/Looks/Glass", {0.2f, 0.6f, 0.9f}, 0.2f);
        host.set("/Looks/Glass", "inputs:opacity", HostValue::floatValue(0.5f));
        host.addCamera("/Camera", lookingAlongY({0, 0, 0}, 0));
        host.addCamera("/Other", lookingAlongY({0.4, -0.5, 0.1}, -2));
        addBox(host, "/Wall", {-20, 6, -20}, {20, 6.5, 20}, "/Looks/Grey");
        addBox(host, "/Front", {-1.0, 3, -0.5}, {-0.5, 3.5, 0.2}, "/Looks/Red");
        addBox(host, "/Hidden", {-0.5, 9, -0.4}, {0.5, 10, 0.4}, "/Looks/Red");
        addBox(host, "/Pane", {0.1, 2.5, 0.1}, {0.8, 2.6, 0.5}, "/Looks/Glass");
        addBox(host, "/HiddenGlass", {0.6, 9, -0.3}, {1.2, 9.5, 0.3}, "/Looks/Glass");
        addBox(host, "/Crowd/Prototypes/Crate", {-0.15, -0.15, -0.15}, {0.15, 0.15, 0.15}, "/Looks/Red");
        std::vector<std::array<float, 3>> positions;
        for (int i = 0; i < kCrowdInFront; ++i) positions.push_back({0.2f + 0.35f * float(i), 4.0f, -0.2f});
        for (int i = 0; i < kCrowdBehind; ++i) positions.push_back({-1.0f + 0.4f * float(i), 8.0f + float(i % 3), 0.0f});
        host.addPrim("instancer", "/Crowd",
                     {{"prototypes", HostValue::paths({"/Crowd/Prototypes/Crate"})},
                      {"protoIndices", HostValue::intArray(std::vector<int32_t>(positions.size(), 0))},
                      {"positions", HostValue::points(positions)}});
        std::map<std::string, HostValue> sun = {{"inputs:intensity", HostValue::floatValue(3.0f)},
                                                {"inputs:normalize", HostValue::boolean(true)},
                                                {"inputs:angle", HostValue::floatValue(0.5f)}};
        host.addPrim("distantLight", "/Sun", sun, lightPointingAlong({-0.4, 0.6, -0.7}));
        host.addRenderBuffer("/Buffers/color", "float32Vec4", width, height);
        host.addRenderBuffer("/Buffers/id", "int32", width, height);
    }

    // Moves a prim as a host does: the new transform, and the prim marked dirty.
    void move(const std::string& path, const Matrix& transform) {
        host.setTransform(path, transform);
        ASSERT_EQ(host.api().markDirty(host.delegate(), path.c_str(), OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    }

    // Opens the camera's shutter over [-0.5, 0.5] and moves `path` 0.4 units along x within it.
    void moveWithinTheShutter(const std::string& path) {
        host.set("/Camera", "shutter:open", HostValue::doubleValue(-0.5));
        host.set("/Camera", "shutter:close", HostValue::doubleValue(0.5));
        host.setTransformMotion(path, -0.5, translation(-0.2, 0, 0), 0.5, translation(0.2, 0, 0));
    }

    using Frame = CulledFrame;
    Frame render(const std::string& camera) { return renderCulledFrame(host, camera); }
};

// The same frame from both scenes: identical colour and ids, pixel for pixel.
void expectSameImage(const WalledScene::Frame& culled, const WalledScene::Frame& drawn, const std::string& frame) {
    ASSERT_EQ(culled.color.size(), drawn.color.size());
    size_t differing = 0;
    for (size_t i = 0; i < culled.color.size(); ++i) differing += culled.color[i] != drawn.color[i];
    EXPECT_EQ(differing, 0u) << frame << ": colour channels that differ with culling";
    EXPECT_EQ(culled.ids, drawn.ids) << frame;
}

// Three frames of the still camera: the same images with culling as without, frame `f` culling
// `expected(f)` instances.
void expectCulledOverThreeFrames(WalledScene& culled, WalledScene& drawn, uint64_t (*expected)(int)) {
    for (int frame = 0; frame < 3; ++frame) {
        WalledScene::Frame f = culled.render("/Camera");
        expectSameImage(f, drawn.render("/Camera"), "frame " + std::to_string(frame));
        EXPECT_EQ(f.culling.instancesCulled, expected(frame)) << "frame " << frame;
    }
}

// Six frames of a camera moving and turning: the same images with culling as without, and the
// frames after the first cull what the wall keeps hiding.
void expectSameImagesAlongACameraPath(WalledScene& culled, WalledScene& drawn) {
    uint64_t culledWhileMoving = 0;
    for (int frame = 0; frame < 6; ++frame) {
        const Matrix view = lookingAlongY({0.06 * frame, 0.1 * frame, 0.02 * frame}, 0.5 * frame);
        culled.move("/Camera", view);
        drawn.move("/Camera", view);
        WalledScene::Frame f = culled.render("/Camera");
        expectSameImage(f, drawn.render("/Camera"), "frame " + std::to_string(frame));
        if (frame > 0) culledWhileMoving += f.culling.instancesCulled;
    }
    EXPECT_GT(culledWhileMoving, 0u) << "the moving camera's frames cull what the wall keeps hiding";
}

TEST(OcclusionCulling, TheFirstFrameDrawsEverythingAndTheNextCullsWhatTheWallHides) {
    WalledScene culled(true), drawn(false);
    WalledScene::Frame first = culled.render("/Camera");
    expectSameImage(first, drawn.render("/Camera"), "first frame");
    // Nothing to reproject yet: every draw is drawn.
    EXPECT_EQ(first.culling.drawsCulled, 0u);
    EXPECT_EQ(first.culling.instancesCulled, 0u);
    EXPECT_EQ(first.culling.draws, 6u) << "the wall, the two boxes, the two glass ones and the crates";
    EXPECT_EQ(first.culling.instances, uint64_t(5 + kCrowdInFront + kCrowdBehind));

    WalledScene::Frame second = culled.render("/Camera");
    expectSameImage(second, drawn.render("/Camera"), "second frame");
    // The boxes behind the wall, opaque and transparent, are culled whole; the crates behind it
    // leave the crowd's draw.
    EXPECT_EQ(second.culling.drawsCulled, 2u);
    EXPECT_EQ(second.culling.instancesCulled, uint64_t(2 + kCrowdBehind));
    EXPECT_EQ(second.culling.trianglesCulled, uint64_t(12 * (2 + kCrowdBehind)));
    EXPECT_EQ(renderStats(culled.host).trianglesDrawn, uint64_t(12 * (3 + kCrowdInFront)));
    EXPECT_EQ(renderStats(drawn.host).trianglesDrawn, uint64_t(12 * (5 + kCrowdInFront + kCrowdBehind)));
}

// A moving camera, then a cut to another camera and back: every frame the same image with culling
// as without; the cut frames draw everything, the moving ones still cull what stays hidden.
TEST(OcclusionCulling, ACameraPathWithACutRendersTheSameImages) {
    WalledScene culled(true), drawn(false);
    expectSameImagesAlongACameraPath(culled, drawn);

    WalledScene::Frame cut = culled.render("/Other");
    expectSameImage(cut, drawn.render("/Other"), "cut");
    EXPECT_EQ(cut.culling.instancesCulled, 0u) << "a camera cut has no history: it draws everything";
    WalledScene::Frame after = culled.render("/Other");
    expectSameImage(after, drawn.render("/Other"), "after the cut");
    EXPECT_GT(after.culling.instancesCulled, 0u);
    WalledScene::Frame back = culled.render("/Camera");
    expectSameImage(back, drawn.render("/Camera"), "back to the first camera");
    EXPECT_EQ(back.culling.instancesCulled, 0u);
}

// With MSAA the coverage buffer is made from each pixel's farthest sample depth.
TEST(OcclusionCulling, MultisampledFramesCullWhatTheWallHides) {
    WalledScene culled(true), drawn(false);
    setNumber(culled.host, "msaa", 4);
    setNumber(drawn.host, "msaa", 4);
    expectCulledOverThreeFrames(culled, drawn, [](int frame) { return uint64_t(frame == 0 ? 0 : 2 + kCrowdBehind); });
}

// A box moving within the shutter (motion blur): a still's frames each see it at their own part of
// the shutter, so no frame's depth stands for the next one, and nothing is culled.
TEST(OcclusionCulling, MotionWithinTheShutterCullsNothing) {
    WalledScene culled(true), drawn(false);
    for (WalledScene* scene : {&culled, &drawn}) scene->moveWithinTheShutter("/Front");
    expectCulledOverThreeFrames(culled, drawn, [](int) { return uint64_t(0); });
}

// A moving occluder: the frame after the wall moves draws everything (its depth no longer stands),
// and what the wall uncovers is drawn.
TEST(OcclusionCulling, AMovedOccluderCullsNothingUntilItsDepthIsRenderedAgain) {
    WalledScene culled(true), drawn(false);
    culled.render("/Camera");
    drawn.render("/Camera");
    EXPECT_GT(culled.render("/Camera").culling.instancesCulled, 0u);
    drawn.render("/Camera");
    // The wall drops below the view: what was behind it is in plain sight.
    culled.move("/Wall", translation(0, 0, -30));
    drawn.move("/Wall", translation(0, 0, -30));
    WalledScene::Frame moved = culled.render("/Camera");
    expectSameImage(moved, drawn.render("/Camera"), "after the wall moved");
    EXPECT_EQ(moved.culling.instancesCulled, 0u);
    WalledScene::Frame next = culled.render("/Camera");
    expectSameImage(next, drawn.render("/Camera"), "the frame after");
    EXPECT_EQ(next.culling.instancesCulled, 0u) << "nothing is hidden any more";
}

// The GPU route (two phases within the frame): the first frame has no history, so its early phase
// draws every candidate and none is left out; from the next on, what the wall hides is culled
// (transparent draws are not: the transparent pass draws them as they are).
TEST(GpuOcclusionCulling, TheFirstFrameDrawsEverythingAndTheNextCullsWhatTheWallHides) {
    WalledScene culled(true, kGpu), drawn(false);
    WalledScene::Frame first = culled.render("/Camera");
    expectSameImage(first, drawn.render("/Camera"), "first frame");
    EXPECT_EQ(first.culling.instancesCulled, 0u);
    EXPECT_EQ(first.culling.draws, 6u);
    for (int frame = 1; frame < 3; ++frame) {
        WalledScene::Frame next = culled.render("/Camera");
        expectSameImage(next, drawn.render("/Camera"), "frame " + std::to_string(frame));
        EXPECT_EQ(next.culling.drawsCulled, 1u) << "the opaque box behind the wall";
        EXPECT_EQ(next.culling.instancesCulled, uint64_t(1 + kCrowdBehind));
        EXPECT_EQ(next.culling.trianglesCulled, uint64_t(12 * (1 + kCrowdBehind)));
        EXPECT_EQ(renderStats(culled.host).trianglesDrawn, uint64_t(12 * (4 + kCrowdInFront)));
    }
}

// A frame whose sides are no power of two: the pyramid's levels end in texels that cover part of
// their span (their farthest depth is that of the pixels there are), with the image's edges along
// the hidden box's rectangle at the coarser levels.
TEST(GpuOcclusionCulling, AFrameOfOddSizeCullsWhatTheWallHides) {
    for (auto [width, height] : {std::pair{67, 37}, std::pair{33, 95}}) {
        WalledScene culled(true, kGpu, width, height), drawn(false, kGpu, width, height);
        for (int frame = 0; frame < 2; ++frame) {
            WalledScene::Frame f = culled.render("/Camera");
            const std::string name = std::to_string(width) + "x" + std::to_string(height);
            expectSameImage(f, drawn.render("/Camera"), name + " frame " + std::to_string(frame));
            EXPECT_EQ(f.culling.instancesCulled, frame == 0 ? 0u : uint64_t(1 + kCrowdBehind)) << name;
        }
    }
}

// A moving camera, a cut and back: the same image with culling as without in every frame. The test
// is this frame's own depth, so a cut culls as well as any frame (the last frame's visible set is
// only the first guess of what to draw early).
TEST(GpuOcclusionCulling, ACameraPathWithACutRendersTheSameImages) {
    WalledScene culled(true, kGpu), drawn(false);
    expectSameImagesAlongACameraPath(culled, drawn);
    WalledScene::Frame cut = culled.render("/Other");
    expectSameImage(cut, drawn.render("/Other"), "cut");
    EXPECT_GT(cut.culling.instancesCulled, 0u) << "the cut's own depth hides what lies behind the wall";
    WalledScene::Frame back = culled.render("/Camera");
    expectSameImage(back, drawn.render("/Camera"), "back to the first camera");
    EXPECT_EQ(back.culling.instancesCulled, uint64_t(1 + kCrowdBehind));
}

// With MSAA the depth pyramid takes each pixel's farthest sample.
TEST(GpuOcclusionCulling, MultisampledFramesCullWhatTheWallHides) {
    WalledScene culled(true, kGpu), drawn(false);
    setNumber(culled.host, "msaa", 4);
    setNumber(drawn.host, "msaa", 4);
    expectCulledOverThreeFrames(culled, drawn, [](int frame) { return uint64_t(frame == 0 ? 0 : 1 + kCrowdBehind); });
}

// A box moving within the shutter is never culled (its bounds hold one time of it); what stands
// still behind the wall still is, as each frame tests its own depth.
TEST(GpuOcclusionCulling, MotionWithinTheShutterCullsOnlyWhatStandsStill) {
    WalledScene culled(true, kGpu), drawn(false);
    for (WalledScene* scene : {&culled, &drawn}) scene->moveWithinTheShutter("/Hidden");
    expectCulledOverThreeFrames(culled, drawn, [](int frame) { return uint64_t(frame == 0 ? 0 : kCrowdBehind); });
}

// What an occluder uncovers is drawn in the very frame it is uncovered: the late phase finds it
// visible against this frame's depth, though the last frame culled it.
TEST(GpuOcclusionCulling, WhatAMovedOccluderUncoversIsDrawnInTheSameFrame) {
    WalledScene culled(true, kGpu), drawn(false);
    culled.render("/Camera");
    drawn.render("/Camera");
    EXPECT_EQ(culled.render("/Camera").culling.instancesCulled, uint64_t(1 + kCrowdBehind));
    drawn.render("/Camera");
    culled.move("/Wall", translation(0, 0, -30));
    drawn.move("/Wall", translation(0, 0, -30));
    WalledScene::Frame moved = culled.render("/Camera");
    expectSameImage(moved, drawn.render("/Camera"), "after the wall moved");
    EXPECT_EQ(moved.culling.instancesCulled, 0u) << "nothing is hidden any more";
    int32_t hiddenId = -1;
    ASSERT_EQ(culled.host.api().getPrimId(culled.host.delegate(), "/Hidden", &hiddenId), OBSCURA_OK);
    EXPECT_GT(std::count(moved.ids.begin(), moved.ids.end(), hiddenId), 0) << "the box the wall hid is drawn";
}

// The GPU route culls the shadow views too, each against its own depth: crates under a roof are
// hidden from the sun by it (the camera, looking under the roof, sees them). As the sun turns every
// frame, every cascade is rendered again, and crates at the roof's edge step out of its shadow:
// the shadows, and so the images, are those of the scene without culling, frame by frame.
struct RoofedScene {
    TestHost host;
    explicit RoofedScene(bool culling) {
        setBool(host, "occlusionCulling", culling);
        setToken(host, "occlusionCulling:route", kGpu);
        addMaterial(host, "/Looks/Grey", {0.5f, 0.5f, 0.5f}, 0.6f);
        addMaterial(host, "/Looks/Red", {0.8f, 0.1f, 0.1f}, 0.4f);
        host.addCamera("/Camera", lookingAlongY({0, 0, 0}, -8));
        addBox(host, "/Ground", {-10, 2, -1.2}, {10, 30, -1.0}, "/Looks/Grey");
        addBox(host, "/Roof", {-1.2, 5, 0.6}, {1.2, 9, 0.7}, "/Looks/Grey");
        addBox(host, "/Crates/Prototypes/Crate", {-0.15, -0.15, -0.15}, {0.15, 0.15, 0.15}, "/Looks/Red");
        std::vector<std::array<float, 3>> positions;
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 3; ++j) positions.push_back({-1.4f + 0.4f * float(i), 5.5f + 1.2f * float(j), -0.85f});
        host.addPrim("instancer", "/Crates",
                     {{"prototypes", HostValue::paths({"/Crates/Prototypes/Crate"})},
                      {"protoIndices", HostValue::intArray(std::vector<int32_t>(positions.size(), 0))},
                      {"positions", HostValue::points(positions)}});
        host.addPrim("distantLight", "/Sun",
                     {{"inputs:intensity", HostValue::floatValue(3.0f)},
                      {"inputs:normalize", HostValue::boolean(true)},
                      {"inputs:angle", HostValue::floatValue(0.5f)}},
                     lightPointingAlong({0, 0.1, -1}));
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    }
    void turnSun(int frame) {
        host.setTransform("/Sun", lightPointingAlong({0.12 * frame, 0.1, -1}));
        ASSERT_EQ(host.api().markDirty(host.delegate(), "/Sun", OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    }
};

TEST(GpuOcclusionCulling, ShadowViewsCullWhatTheirOwnDepthHidesAndCastTheSameShadows) {
    RoofedScene culled(true), drawn(false);
    for (int frame = 0; frame < 5; ++frame) {
        culled.turnSun(frame);
        drawn.turnSun(frame);
        CulledFrame f = renderCulledFrame(culled.host, "/Camera");
        expectSameImage(f, renderCulledFrame(drawn.host, "/Camera"), "frame " + std::to_string(frame));
    }
    // The shadow views were culled on the GPU, in both phases, in the frame just rendered.
    uint32_t count = 0;
    ASSERT_EQ(culled.host.api().getPassTimings(culled.host.delegate(), nullptr, &count), OBSCURA_OK);
    std::vector<ObscuraPassTiming> timings(count);
    ASSERT_EQ(culled.host.api().getPassTimings(culled.host.delegate(), timings.data(), &count), OBSCURA_OK);
    std::vector<std::string> passes;
    for (const ObscuraPassTiming& timing : timings) passes.push_back(timing.pass);
    for (const char* pass : {"shadow_occlusion_cull_early", "shadow_maps", "shadow_hi_z", "shadow_occlusion_cull_late",
                             "shadow_maps_late"})
        EXPECT_NE(std::find(passes.begin(), passes.end(), pass), passes.end()) << pass;
}

// View frustum culling, always on: boxes wholly outside the view (behind the eye, far to one side,
// instances beyond the frame) are not drawn, a box across the frame's edge is, and the off-screen
// prims change no pixel: the image equals that of the scene without them.
struct FrustumScene {
    TestHost host;
    explicit FrustumScene(bool offScreenPrims) {
        addMaterial(host, "/Looks/Grey", {0.5f, 0.5f, 0.5f}, 0.6f);
        host.addCamera("/Camera", lookingAlongY({0, 0, 0}, 0));
        host.addPrim("domeLight", "/Sky", {{"inputs:intensity", HostValue::floatValue(1.0f)}});
        addBox(host, "/InView", {-0.3, 5, -0.3}, {0.3, 5.5, 0.3}, "/Looks/Grey");
        // The view is about 2.1 units wide at 5 units (the default 50 mm lens): this box crosses
        // its right edge.
        addBox(host, "/Edge", {0.9, 5, -0.2}, {1.5, 5.4, 0.2}, "/Looks/Grey");
        addBox(host, "/Crowd/Prototypes/Crate", {-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}, "/Looks/Grey");
        host.addPrim("instancer", "/Crowd",
                     {{"prototypes", HostValue::paths({"/Crowd/Prototypes/Crate"})},
                      {"protoIndices", HostValue::intArray({0, 0, 0, 0})},
                      {"positions", HostValue::points({{-0.5f, 6, 0.3f}, {0.5f, 6, 0.3f}, {-30, 6, 0}, {0, -8, 0}})}});
        if (offScreenPrims) {
            addBox(host, "/Behind", {-0.5, -6, -0.5}, {0.5, -5, 0.5}, "/Looks/Grey");
            addBox(host, "/FarSide", {20, 5, -0.5}, {21, 6, 0.5}, "/Looks/Grey");
        }
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
    }
    CulledFrame render() { return renderCulledFrame(host, "/Camera"); }
};

TEST(FrustumCulling, WhatLiesOutsideTheViewIsNotDrawnAndChangesNoPixel) {
    FrustumScene with(true), without(false);
    WalledScene::Frame frame = with.render();
    expectSameImage(frame, without.render(), "with and without the off-screen prims");
    EXPECT_EQ(frame.culling.drawsOutsideView, 2u) << "the box behind the eye and the one far to the side";
    EXPECT_EQ(frame.culling.instancesOutsideView, 4u) << "those two and the crowd's two crates out of the frame";
    EXPECT_EQ(frame.culling.instancesCulled, 0u) << "occlusion culling is off";
    int32_t edgeId = -1;
    ASSERT_EQ(with.host.api().getPrimId(with.host.delegate(), "/Edge", &edgeId), OBSCURA_OK);
    EXPECT_GT(std::count(frame.ids.begin(), frame.ids.end(), edgeId), 0) << "the box across the frame's edge is drawn";
}

}  // namespace
}  // namespace obscura::test
