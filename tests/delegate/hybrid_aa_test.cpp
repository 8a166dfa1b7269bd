// Hybrid anti-aliasing (seed 004 "Hybrid anti-aliasing solution"): objects nearer than
// taa:hybridDistance are drawn on the pixel grid (no jitter), keep no temporal history and get
// edge AA (morphological, passes/edge_aa.h); farther ones stay temporal (SMAA 1TX). Measured
// against the ground truth: the supersampled image for emitters (pure coverage), the reference
// mode's jittered sub-frames where lights shade. Printed: PSNR per region and configuration.
#include "tests/delegate/camera_scene.h"
#include "tests/delegate/render_fixture.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

namespace obscura::test {
namespace {

constexpr int kSupersampling = 8;

// PSNR (peak 1) over the pixels where `mask` is set, of the RGB values passed through `transfer`.
double maskedPsnr(const std::vector<float>& a, const std::vector<float>& b, const std::vector<bool>& mask,
                  float (*transfer)(float) = nullptr) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t p = 0; p < mask.size(); ++p) {
        if (!mask[p]) continue;
        for (int c = 0; c < 3; ++c) {
            float x = a[p * 4 + c], y = b[p * 4 + c];
            if (transfer) x = transfer(x), y = transfer(y);
            sum += double(x - y) * double(x - y);
        }
        count += 3;
    }
    EXPECT_GT(count, 0u);
    return 10.0 * std::log10(double(count) / std::max(sum, 1e-30));
}

float reinhard(float x) { return x / (1.0f + x); }

std::vector<float> rgbaOf(const image::Image& img) {
    std::vector<float> rgba(size_t(img.width) * img.height * 4, 1.0f);
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
        for (int c = 0; c < 3; ++c) rgba[p * 4 + c] = img.pixels[p * 3 + c];
    return rgba;
}

// Pixels within one pixel of where `ids` holds `id`: an object and the edge around it.
std::vector<bool> around(const std::vector<int32_t>& ids, int32_t id) {
    std::vector<bool> mask(ids.size(), false);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int nx = std::clamp(x + dx, 0, kWidth - 1), ny = std::clamp(y + dy, 0, kHeight - 1);
                    if (ids[size_t(ny) * kWidth + nx] == id) mask[size_t(y) * kWidth + x] = true;
                }
    return mask;
}

// The camera of the lit-plane scenes at (x, 0, 5) looking down -Z, scene units in metres (so
// taa:hybridDistance is in scene units), colour and prim id buffers.
struct CameraAndBuffers {
    TestHost host;
    CameraAndBuffers() {
        host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength,
                       kLitPlaneAperture);
        setNumber(host, "metersPerUnit", 1.0);
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/primId", "int32", kWidth, kHeight);
    }
    std::vector<float> render() {
        EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}, {"primId", "/Buffers/primId"}}), OBSCURA_OK)
            << host.lastError();
        EXPECT_TRUE(host.loggedErrors().empty());
        return host.readFloats("/Buffers/color");
    }
    int32_t id(const char* path) {
        int32_t id = -1;
        EXPECT_EQ(host.api().getPrimId(host.delegate(), path, &id), OBSCURA_OK);
        return id;
    }
    // Moves the camera sideways; the same x marks it changed without moving it: a changing frame.
    void moveCamera(double x) {
        host.setTransform("/Camera", translation(x, 0, kLitPlaneCameraDistance));
        ASSERT_EQ(host.api().markDirty(host.delegate(), "/Camera", OBSCURA_DIRTY_TRANSFORM), OBSCURA_OK);
    }
};

// White emitters over black seen from (0, 0, 5): a square turned 20 degrees 2 units from the camera
// and a second one 5 units away, so that a hybrid distance between them splits them.
struct TwoDepthScene : CameraAndBuffers {
    TwoDepthScene() {
        addMaterial(host, "/Looks/White", {0, 0, 0}, 1.0f, 0.0f, {1, 1, 1});
        addPlane(host, "/Near", "/Looks/White", 0.12, turnedAndMoved(20, -0.2, 0.05, 3));
        addPlane(host, "/Far", "/Looks/White", 0.3, turnedAndMoved(-25, 0.5, -0.2, 0));
        host.addRenderBuffer("/Buffers/super", "float32Vec4", kWidth * kSupersampling, kHeight * kSupersampling);
    }
    std::vector<float> renderUntilConverged() {
        std::vector<float> color = render();
        for (int renders = 1; !renderStats(host).converged && renders < 100; ++renders) color = render();
        return color;
    }
    std::vector<float> supersampled() {
        setNumber(host, "taa", 0.0);
        EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/super"}}), OBSCURA_OK) << host.lastError();
        setNumber(host, "taa", 1.0);
        return rgbaOf(boxDownsample(host.readFloats("/Buffers/super"), kWidth * kSupersampling,
                                    kHeight * kSupersampling, kSupersampling));
    }
    void touch() { moveCamera(0.0); }
};

// Edge AA alone (every object near) while the scene changes: no jitter, so two frames of an
// unchanged view are the same image; its edges are much closer to the truth than the aliased
// image, and pixels away from edges are untouched.
TEST(HybridAa, EdgeAaSmoothsNearEdgesWithoutJitter) {
    TwoDepthScene s;
    std::vector<float> truth = s.supersampled();
    setNumber(s.host, "taa", 0.0);
    std::vector<float> aliased = s.render();
    setNumber(s.host, "taa", 1.0);
    setNumber(s.host, "taa:hybridDistance", 100.0);
    s.touch();
    std::vector<float> first = s.render();
    EXPECT_TRUE(ranPass(s.host, "edge_aa_blend"));
    s.touch();
    std::vector<float> edgeAa = s.render();
    EXPECT_EQ(first, edgeAa) << "nothing near is jittered or accumulated";

    std::vector<bool> all(truth.size() / 4, true);
    std::vector<bool> edges(all.size(), false);  // pixels the truth covers partly
    int untouched = 0, flat = 0;
    for (size_t p = 0; p < all.size(); ++p) {
        edges[p] = truth[p * 4] > 0.02f && truth[p * 4] < 0.98f;
        int x = int(p % kWidth), y = int(p / kWidth);
        bool awayFromEdges = true;
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                int nx = std::clamp(x + dx, 0, kWidth - 1), ny = std::clamp(y + dy, 0, kHeight - 1);
                awayFromEdges &= truth[(size_t(ny) * kWidth + nx) * 4] == truth[p * 4];
            }
        if (!awayFromEdges) continue;
        ++flat;
        untouched += edgeAa[p * 4] == aliased[p * 4];
    }
    double plainAll = maskedPsnr(aliased, truth, all), edgeAll = maskedPsnr(edgeAa, truth, all);
    double plainEdges = maskedPsnr(aliased, truth, edges), edgeEdges = maskedPsnr(edgeAa, truth, edges);
    std::printf("[ metric ] edge AA vs %dx supersampled (64x64, two turned squares): whole image no AA %.2f dB, "
                "edge AA %.2f dB; over the %zu partly covered pixels no AA %.2f dB, edge AA %.2f dB; %d of %d "
                "pixels away from edges unchanged\n",
                kSupersampling, plainAll, edgeAll, size_t(std::count(edges.begin(), edges.end(), true)), plainEdges,
                edgeEdges, untouched, flat);
    EXPECT_GT(edgeAll, plainAll + 6.0);
    EXPECT_GT(edgeEdges, plainEdges + 6.0);
    EXPECT_EQ(untouched, flat);
}

// The split, while the scene changes: with the hybrid distance between the squares, the near one
// is drawn on the pixel grid (the same in every frame) and the far one jitters. A still then
// accumulates jittered frames of both and converges as temporal AA alone does.
TEST(HybridAa, ChangingFramesSplitByDistanceStillsConvergeEverywhere) {
    TwoDepthScene temporal, hybrid;
    std::vector<float> truth = temporal.supersampled();
    std::vector<float> temporalOnly = temporal.renderUntilConverged();
    std::vector<int32_t> ids = temporal.host.readInts("/Buffers/primId");
    std::vector<bool> nearMask = around(ids, temporal.id("/Near")), farMask = around(ids, temporal.id("/Far"));
    setNumber(hybrid.host, "taa:hybridDistance", 3.5);
    std::vector<float> frames[3];
    for (auto& frame : frames) {
        hybrid.touch();
        frame = hybrid.render();
        EXPECT_TRUE(ranPass(hybrid.host, "edge_aa_blend"));
    }
    bool nearSteady = true, farJitters = false;
    for (size_t p = 0; p < nearMask.size(); ++p) {
        if (nearMask[p] && !farMask[p]) nearSteady &= frames[1][p * 4] == frames[2][p * 4];
        if (farMask[p] && !nearMask[p]) farJitters |= frames[1][p * 4] != frames[2][p * 4];
    }
    EXPECT_TRUE(nearSteady) << "the near square is not jittered";
    EXPECT_TRUE(farJitters) << "the far square is";
    double nearChanging = maskedPsnr(frames[2], truth, nearMask);
    std::vector<float> converged = hybrid.renderUntilConverged();
    EXPECT_FALSE(ranPass(hybrid.host, "edge_aa_blend"));
    double nearTemporal = maskedPsnr(temporalOnly, truth, nearMask), nearHybrid = maskedPsnr(converged, truth, nearMask);
    double farTemporal = maskedPsnr(temporalOnly, truth, farMask), farHybrid = maskedPsnr(converged, truth, farMask);
    std::printf("[ metric ] vs %dx supersampled: near square edge-anti-aliased while changing %.2f dB; converged "
                "still: near square temporal AA %.2f dB, hybrid %.2f dB; far square temporal AA %.2f dB, hybrid "
                "%.2f dB\n",
                kSupersampling, nearChanging, nearTemporal, nearHybrid, farTemporal, farHybrid);
    EXPECT_NEAR(nearHybrid, nearTemporal, 0.5);
    EXPECT_NEAR(farHybrid, farTemporal, 0.5);
}

TEST(HybridAa, ANegativeDistanceIsRefused) {
    TwoDepthScene s;
    double distance = -1.0;
    ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &distance};
    EXPECT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "taa:hybridDistance", &v), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s.host.lastError()).find("taa:hybridDistance"), std::string::npos) << s.host.lastError();
    s.render();
    EXPECT_FALSE(ranPass(s.host, "edge_aa_blend"));
}

// A lit scene for the seed's case: a glossy metal card near the camera, where a sphere light's
// highlight slides across the card as the camera moves (view-dependent shading), and a lit wall
// with a thin emissive bar far behind. The camera pans right; every frame is measured against the
// reference mode's 64 sub-frames of the same view. Measured (mean PSNR, 1.5 px/frame): near card
// no AA 32.26 dB, temporal AA 26.05 dB, hybrid 30.16 dB; the rest 23.83 / 24.03 / 24.15 dB; whole
// 24.14 / 24.02 / 24.29 dB. Edge AA on everything did better still in motion here (31.24 / 25.10 /
// 25.40 dB: the thin bar flickers under temporal AA in motion), and worse in a still (the test above).
struct GlossyScene : CameraAndBuffers {
    GlossyScene() {
        setNumber(host, "ssao", 0.0);
        addMaterial(host, "/Looks/Metal", {0.9f, 0.9f, 0.9f}, 0.25f, 1.0f);
        addMaterial(host, "/Looks/Wall", {0.5f, 0.5f, 0.5f}, 0.8f, 0.0f);
        addMaterial(host, "/Looks/Glow", {0, 0, 0}, 1.0f, 0.0f, {1.5f, 1.5f, 1.5f});
        addPlane(host, "/Near", "/Looks/Metal", 0.15, turnedAndMoved(20, 0.0, 0.05, 3));
        addPlane(host, "/Wall", "/Looks/Wall", 3.0, translation(0, 0, -0.5));
        host.addPrim("mesh", "/Bar",
                     {{"points", HostValue::points({{-0.012f, -0.7f, 0}, {0.012f, -0.7f, 0}, {0.012f, 0.7f, 0},
                                                    {-0.012f, 0.7f, 0}})},
                      {"faceVertexCounts", HostValue::intArray({4})},
                      {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                      {"subdivisionScheme", HostValue::token("none")},
                      {"material:binding", HostValue::path("/Looks/Glow")}},
                     turnedAndMoved(7, 0.55, 0, 0));
        host.addPrim("sphereLight", "/Bulb",
                     {{"inputs:intensity", HostValue::floatValue(40.0f)}, {"inputs:radius", HostValue::floatValue(0.04f)}},
                     translation(-0.05, 0.1, 4.0));
        host.addPrim("distantLight", "/Sun", {{"inputs:intensity", HostValue::floatValue(1.5f)}},
                     lightPointingAlong({0.2, -0.3, -1}));
    }
};

struct RegionPsnr {
    double nearLinear = 0, nearToneMapped = 0, farLinear = 0, allLinear = 0, allToneMapped = 0;
};

TEST(HybridAa, ViewDependentShadingNearAMovingCamera) {
    const double pixel = 2.0 * kLitPlaneTanHalfFov * kLitPlaneCameraDistance / kWidth;  // at the bar's depth
    struct Config {
        const char* name;
        double taa;
        double hybridDistance;
    };
    const Config configs[] = {{"no AA", 0, 0}, {"temporal AA", 1, 0}, {"hybrid", 1, 3.5}, {"edge AA", 1, 100}};
    for (double pixelsPerFrame : {0.5, 1.5}) {
        GlossyScene reference;
        setNumber(reference.host, "reference", 64);
        std::vector<std::unique_ptr<GlossyScene>> scenes;
        for (const Config& c : configs) {
            scenes.push_back(std::make_unique<GlossyScene>());
            setNumber(scenes.back()->host, "taa", c.taa);
            setNumber(scenes.back()->host, "taa:hybridDistance", c.hybridDistance);
        }
        std::vector<RegionPsnr> sums(std::size(configs));
        int counted = 0;
        for (int frame = 0; frame < 12; ++frame) {
            double x = pixelsPerFrame * pixel * (frame - 6);
            reference.moveCamera(x);
            std::vector<float> truth = reference.render();
            std::vector<std::vector<float>> colors;
            for (auto& scene : scenes) {
                scene->moveCamera(x);
                colors.push_back(scene->render());
            }
            std::vector<int32_t> ids = scenes[0]->host.readInts("/Buffers/primId");
            int32_t nearId = scenes[0]->id("/Near");
            std::vector<bool> nearMask = around(ids, nearId), farMask(nearMask.size()), all(nearMask.size(), true);
            for (size_t p = 0; p < farMask.size(); ++p) farMask[p] = !nearMask[p];
            for (size_t i = 0; i < scenes.size(); ++i) {
                const std::vector<float>& color = colors[i];
                if (frame < 3) continue;  // the history fills up
                sums[i].nearLinear += maskedPsnr(color, truth, nearMask);
                sums[i].nearToneMapped += maskedPsnr(color, truth, nearMask, reinhard);
                sums[i].farLinear += maskedPsnr(color, truth, farMask);
                sums[i].allLinear += maskedPsnr(color, truth, all);
                sums[i].allToneMapped += maskedPsnr(color, truth, all, reinhard);
            }
            counted += frame >= 3;
        }
        for (size_t i = 0; i < scenes.size(); ++i)
            std::printf("[ metric ] camera panning %.1f px/frame, mean PSNR vs the reference (64 sub-frames) over %d "
                        "frames, %-11s: near card %.2f dB (tone-mapped %.2f dB), the rest %.2f dB, whole %.2f dB (tone-mapped %.2f dB)\n",
                        pixelsPerFrame, counted, configs[i].name, sums[i].nearLinear / counted, sums[i].nearToneMapped / counted,
                        sums[i].farLinear / counted, sums[i].allLinear / counted, sums[i].allToneMapped / counted);
        // The seed's claim, measured: on the near card temporal AA loses to view-dependent shading
        // and hybrid AA wins it back, the rest stays temporal, the whole image gains.
        const RegionPsnr temporal = sums[1], hybrid = sums[2];
        EXPECT_GT(hybrid.nearLinear, temporal.nearLinear + counted * 1.0) << pixelsPerFrame;
        EXPECT_GT(hybrid.farLinear, temporal.farLinear - counted * 0.3) << pixelsPerFrame;
        EXPECT_GT(hybrid.allLinear, temporal.allLinear) << pixelsPerFrame;
    }
}

}  // namespace
}  // namespace obscura::test
