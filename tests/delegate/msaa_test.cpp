// Deferred MSAA (seed 000 "Deferred MSAA"): with the render setting msaa = 4 an edge converges to
// the supersampled image far better than with one sample; the custom resolve tags silhouettes and
// leaves flat surfaces alone (the share printed against the edge length); a very bright object
// against a dark one resolves to the coverage-weighted mix of the tone-mapped samples (no bright
// outline), which a plain average of the samples would miss by far, and so does a point's sphere
// impostor at the samples its sphere covers; the reference mode and
// temporal AA keep working with it; sample counts the device does not offer are refused.
// Emissive surfaces only (no lights): what reaches a pixel is coverage, so edges are the story.
#include "tests/delegate/camera_scene.h"
#include "tests/delegate/render_fixture.h"

#include <algorithm>
#include <cstdio>

namespace obscura::test {
namespace {

constexpr int kSupersampling = 8;
// A unit square turned 20 degrees (edges at every sub-pixel phase) left of the centre, at z = 0.
constexpr double kSquareTurn = 20.0, kSquareX = -0.3, kSquareHalf = 0.5;
// Vulkan's standard 4x sample locations from the pixel's corner (the device's, on lavapipe).
constexpr std::array<std::array<double, 2>, 4> kFourSamples{{{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625},
                                                              {0.625, 0.875}}};

ObscuraStatus setInt(TestHost& host, const char* name, int32_t value) {
    ObscuraValue v{OBSCURA_VALUE_INT, 0, 1, &value};
    return host.api().setRenderSetting(host.delegate(), name, &v);
}
// The resolve's tone map for grey values (shaders/common/hdr_resolve.glsl): Reinhard on luma.
float reinhard(float v) { return v / (1.0f + v); }
double inverseReinhard(double t) { return t / (1.0 - t); }

std::vector<float> toneMapped(std::vector<float> rgba) {
    for (size_t i = 0; i < rgba.size(); ++i)
        if (i % 4 != 3) rgba[i] = reinhard(rgba[i]);
    return rgba;
}

// The pixels the last render lit per sample, from the delegate's "msaa Nx: ... (T of P)" line.
int taggedPixels(TestHost& host) {
    for (auto it = host.loggedInfos().rbegin(); it != host.loggedInfos().rend(); ++it) {
        if (it->rfind("msaa ", 0) != 0) continue;
        int tagged = -1, total = 0;
        std::sscanf(it->c_str() + it->rfind('('), "(%d of %d)", &tagged, &total);
        return tagged;
    }
    ADD_FAILURE() << "no msaa line was logged";
    return -1;
}

// The square (emission `squareRadiance`) in front of a plane filling the view at z = -1
// (emission `backgroundRadiance`; none: nothing behind), camera at (0, 0, 5) looking down -Z.
struct SquareScene {
    TestHost host;
    explicit SquareScene(float squareRadiance, std::optional<float> backgroundRadiance = std::nullopt) {
        host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength,
                       kLitPlaneAperture);
        addMaterial(host, "/Looks/Square", {0, 0, 0}, 1.0f, 0.0f, {squareRadiance, squareRadiance, squareRadiance});
        addPlane(host, "/Square", "/Looks/Square", kSquareHalf, turnedAndMoved(kSquareTurn, kSquareX, 0, 0));
        if (backgroundRadiance) {
            float b = *backgroundRadiance;
            addMaterial(host, "/Looks/Background", {0, 0, 0}, 1.0f, 0.0f, {b, b, b});
            addPlane(host, "/Background", "/Looks/Background", 10.0, translation(0, 0, -1));
        }
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/super", "float32Vec4", kWidth * kSupersampling, kHeight * kSupersampling);
        setBool(host, "taa", false);
    }
    std::vector<float> renderColor(const char* buffer = "/Buffers/color") {
        EXPECT_EQ(host.render("/Camera", {{"color", buffer}}), OBSCURA_OK) << host.lastError();
        return host.readFloats(buffer);
    }
};

// Pixels per scene unit on the z = 0 plane.
double pixelsPerUnit() { return kWidth / (2.0 * kLitPlaneCameraDistance * kLitPlaneTanHalfFov); }

// Signed distance in pixels from window position (x, y) (pixels from the top-left corner) to the
// square's outline, negative inside.
double distanceToSquare(double x, double y) {
    double worldX = (x / kWidth * 2.0 - 1.0) * kLitPlaneCameraDistance * kLitPlaneTanHalfFov - kSquareX;
    double worldY = (1.0 - y / kHeight * 2.0) * kLitPlaneCameraDistance * kLitPlaneTanHalfFov;
    double a = kSquareTurn * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    double u = std::abs(c * worldX + s * worldY) - kSquareHalf, v = std::abs(-s * worldX + c * worldY) - kSquareHalf;
    double outside = std::hypot(std::max(u, 0.0), std::max(v, 0.0));
    return (outside > 0.0 ? outside : std::max(u, v)) * pixelsPerUnit();
}

// How many of pixel (x, y)'s four samples the square covers; nullopt where a sample lies within
// 0.01 pixels of the outline (the rasteriser's tie-breaking decides those).
std::optional<int> coveredSamples(int x, int y) {
    int covered = 0;
    for (const auto& [sx, sy] : kFourSamples) {
        double d = distanceToSquare(x + sx, y + sy);
        if (std::abs(d) < 0.01) return std::nullopt;
        covered += d < 0.0 ? 1 : 0;
    }
    return covered;
}

TEST(Msaa, EdgesConvergeTowardTheSupersampledImage) {
    SquareScene s(1.0f);
    // Seen through the resolve's tone map: the supersamples are tone-mapped, then box-filtered.
    image::Image truth = boxDownsample(toneMapped(s.renderColor("/Buffers/super")), kWidth * kSupersampling,
                                       kHeight * kSupersampling, kSupersampling);
    image::CompareMetrics one = compareImages(rgbImage(toneMapped(s.renderColor()), kWidth, kHeight), truth);
    ASSERT_EQ(setInt(s.host, "msaa", 4), OBSCURA_OK) << s.host.lastError();
    image::CompareMetrics four = compareImages(rgbImage(toneMapped(s.renderColor()), kWidth, kHeight), truth);
    std::printf("edge vs %dx supersampled (tone-mapped): msaa 1 PSNR %.2f dB SSIM %.4f; msaa 4 PSNR %.2f dB "
                "SSIM %.4f, max error %.3f\n",
                kSupersampling, one.psnr, one.ssim, four.psnr, four.ssim, four.maxAbsError);
    EXPECT_GT(four.psnr, one.psnr + 6.0);
    EXPECT_GT(four.ssim, one.ssim);
}

// Temporal AA until the still converges; returns the renders it took.
int renderUntilConverged(SquareScene& s) {
    setBool(s.host, "taa", true);
    int renders = 0;
    while (renders < 40) {
        ++renders;
        EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << s.host.lastError();
        if (renderStats(s.host).converged) break;
    }
    setBool(s.host, "taa", false);
    return renders;
}

TEST(Msaa, ReferenceModeAndTemporalAaKeepWorking) {
    SquareScene s(1.0f);
    std::vector<float> supersamples = s.renderColor("/Buffers/super");
    image::Image truth = boxDownsample(supersamples, kWidth * kSupersampling, kHeight * kSupersampling, kSupersampling);
    image::Image toneMappedTruth = boxDownsample(toneMapped(supersamples), kWidth * kSupersampling,
                                                 kHeight * kSupersampling, kSupersampling);
    renderUntilConverged(s);
    image::CompareMetrics temporalAlone =
        compareImages(rgbImage(s.host.readFloats("/Buffers/color"), kWidth, kHeight), truth);
    image::CompareMetrics temporalAloneToneMapped =
        compareImages(rgbImage(toneMapped(s.host.readFloats("/Buffers/color")), kWidth, kHeight), toneMappedTruth);
    ASSERT_EQ(setInt(s.host, "msaa", 4), OBSCURA_OK) << s.host.lastError();
    image::CompareMetrics msaa = compareImages(rgbImage(s.renderColor(), kWidth, kHeight), truth);
    // The reference renders its sub-frames with one sample: its own pixel jitter is the truth.
    ASSERT_EQ(setInt(s.host, "reference", 64), OBSCURA_OK);
    image::CompareMetrics reference = compareImages(rgbImage(s.renderColor(), kWidth, kHeight), truth);
    ASSERT_EQ(setInt(s.host, "reference", 0), OBSCURA_OK);
    // Temporal AA over MSAA frames: each jittered frame's edges resolved from four samples. A
    // still's samples resolve them linearly (the tone-mapped weights are for a real-time frame's
    // few samples) and shift them by half the jitter's span, so the mean of the jittered
    // frames is the box-filtered linear integral, nearer to it than temporal AA alone.
    int renders = renderUntilConverged(s);
    image::CompareMetrics temporal = compareImages(rgbImage(s.host.readFloats("/Buffers/color"), kWidth, kHeight), truth);
    image::CompareMetrics temporalToneMapped =
        compareImages(rgbImage(toneMapped(s.host.readFloats("/Buffers/color")), kWidth, kHeight), toneMappedTruth);

    std::printf("vs %dx supersampled (linear): with msaa 4: msaa alone PSNR %.2f dB, reference (64 sub-frames) "
                "PSNR %.2f dB, SMAA 1TX over msaa (%d renders) PSNR %.2f dB SSIM %.4f; SMAA 1TX alone "
                "PSNR %.2f dB; tone-mapped: SMAA 1TX over msaa 4 PSNR %.2f dB, alone %.2f dB\n",
                kSupersampling, msaa.psnr, reference.psnr, renders, temporal.psnr, temporal.ssim, temporalAlone.psnr,
                temporalToneMapped.psnr, temporalAloneToneMapped.psnr);
    EXPECT_GT(reference.psnr, 40.0);
    EXPECT_EQ(renders, 17);
    EXPECT_GT(temporal.psnr, msaa.psnr + 1.0);
    EXPECT_GT(temporal.psnr, temporalAlone.psnr + 1.0);
}

TEST(Msaa, TagsSilhouettesNotFlatSurfaces) {
    // A flat plane turned 60 degrees away fills the view: its samples differ only along the slope.
    {
        SquareScene flat(1.0f);
        Matrix tilted = lightPointingAlong({0, std::sin(kPi / 3), -std::cos(kPi / 3)});
        addPlane(flat.host, "/Floor", "/Looks/Square", 20.0, tilted);
        ASSERT_EQ(flat.host.api().removePrim(flat.host.delegate(), "/Square"), OBSCURA_OK);
        ASSERT_EQ(setInt(flat.host, "msaa", 4), OBSCURA_OK) << flat.host.lastError();
        flat.renderColor();
        EXPECT_EQ(taggedPixels(flat.host), 0) << "a flat surface has no edge";
    }
    SquareScene s(1.0f, 0.25f);
    ASSERT_EQ(setInt(s.host, "msaa", 4), OBSCURA_OK) << s.host.lastError();
    s.renderColor();
    int tagged = taggedPixels(s.host);
    double outline = 8.0 * kSquareHalf * pixelsPerUnit();  // pixels of silhouette
    int pixelsOnOutline = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            std::optional<int> k = coveredSamples(x, y);
            pixelsOnOutline += !k || (*k > 0 && *k < 4) ? 1 : 0;
        }
    std::printf("silhouette of %.1f pixels (%d pixels with samples on both sides): %d pixels tagged (%.2f%% of the "
                "image, %.2f per pixel of outline)\n",
                outline, pixelsOnOutline, tagged, 100.0 * tagged / (kWidth * kHeight), tagged / outline);
    // Every pixel with samples on both sides is tagged, with its 2x2 quad: between one and four
    // tagged pixels per outline pixel. The square's inside (~930 pixels) is not.
    EXPECT_GE(tagged, pixelsOnOutline);
    EXPECT_LE(tagged, 4 * pixelsOnOutline);
}

TEST(Msaa, FlatSurfacesAreLitAsWithOneSample) {
    // A floor seen at a grazing 75 degrees, in the sun with shadow maps: where no pixel is tagged,
    // the pixel-frequency lighting of the resolved G-buffer is the single-sample frame's. (Sample
    // 0's own depth put at the pixel centre would move the floor along the view ray far enough
    // for the shadow map to shadow it.)
    auto render = [](int32_t msaa) {
        SquareScene s(1.0f);
        EXPECT_EQ(s.host.api().removePrim(s.host.delegate(), "/Square"), OBSCURA_OK);
        addMaterial(s.host, "/Looks/Grey", {kLitPlaneAlbedo, kLitPlaneAlbedo, kLitPlaneAlbedo});
        double tilt = 75.0 * kPi / 180.0;
        addPlane(s.host, "/Floor", "/Looks/Grey", 50.0, lightPointingAlong({0, -std::sin(tilt), -std::cos(tilt)}));
        s.host.addPrim("distantLight", "/Sun",
                       {{"inputs:intensity", HostValue::floatValue(3.0f)},
                        {"inputs:normalize", HostValue::boolean(true)},
                        {"inputs:angle", HostValue::floatValue(0.0f)},
                        {"inputs:specular", HostValue::floatValue(0.0f)}},
                       lightPointingAlong({0.3, -0.9, -0.3}));
        EXPECT_EQ(setInt(s.host, "msaa", msaa), OBSCURA_OK) << s.host.lastError();
        std::vector<float> color = s.renderColor();
        if (msaa > 1) EXPECT_EQ(taggedPixels(s.host), 0);
        return color;
    };
    std::vector<float> one = render(1), four = render(4);
    double worst = 0.0;
    for (size_t i = 0; i < one.size(); i += 4) {
        double tolerance = 0.005 * one[i] + smallFloatStep(one[i], 6);
        worst = std::max(worst, std::abs(double(four[i]) - one[i]) / tolerance);
    }
    std::printf("grazing floor in the sun (centre radiance %.3f): msaa 4 vs 1, worst difference %.2f of the "
                "tolerance\n",
                double(one[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 4]), worst);
    EXPECT_LE(worst, 1.0);
}

TEST(Msaa, BrightEdgeAgainstDarkResolvesWithoutOutline) {
    const float bright = 64.0f, dark = 0.02f;
    SquareScene s(bright, dark);
    ASSERT_EQ(setInt(s.host, "msaa", 4), OBSCURA_OK) << s.host.lastError();
    std::vector<float> color = s.renderColor();
    int edgePixels = 0;
    double worstError = 0.0, hdrOutline = 0.0, plainOutline = 0.0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            std::optional<int> k = coveredSamples(x, y);
            if (!k) continue;
            float measured = color[(size_t(y) * kWidth + x) * 4];
            double coverage = *k / 4.0;
            // The display sees the coverage-weighted mix of the tone-mapped samples...
            double mix = coverage * reinhard(bright) + (1.0 - coverage) * reinhard(dark);
            double expected = inverseReinhard(mix);
            // ...where a plain average of the radiance would show the bright side nearly everywhere.
            double plainAverage = coverage * bright + (1.0 - coverage) * dark;
            double tolerance = 0.01 * expected + smallFloatStep(float(expected), 6);
            EXPECT_NEAR(measured, expected, tolerance) << "pixel " << x << ", " << y << " with " << *k << " samples";
            if (*k == 0 || *k == 4) continue;
            ++edgePixels;
            EXPECT_GT(std::abs(plainAverage - expected), 20.0 * tolerance) << "the test could not tell the two apart";
            worstError = std::max(worstError, std::abs(measured - expected) / expected);
            hdrOutline += reinhard(measured) - mix;
            plainOutline += reinhard(float(plainAverage)) - mix;
        }
    std::printf("%d edge pixels of a %.0f-nit square on %.2f nits: worst error %.2f%% of the tone-mapped-weight "
                "resolve; mean display excess over the coverage mix %.4f (a plain average: %.4f)\n",
                edgePixels, double(bright), double(dark), 100.0 * worstError, hdrOutline / edgePixels,
                plainOutline / edgePixels);
    EXPECT_GT(edgePixels, 40);
}

// A point's sphere (an impostor: its cube ray-cast per pixel) covers exactly the samples whose
// lines of sight meet it, as a triangle edge covers those inside it: a bright emissive sphere on a
// dark plane resolves at every pixel to the mix of its analytically covered samples.
TEST(Msaa, SphereImpostorsCoverTheSamplesTheirSphereMeets) {
    const float bright = 64.0f, dark = 0.02f;
    const std::array<double, 3> centre{0.3, -0.1, 0.0};
    const double radius = 0.6;
    TestHost host;
    host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength, kLitPlaneAperture);
    addMaterial(host, "/Looks/Bright", {0, 0, 0}, 1.0f, 0.0f, {bright, bright, bright});
    addMaterial(host, "/Looks/Dark", {0, 0, 0}, 1.0f, 0.0f, {dark, dark, dark});
    addPlane(host, "/Background", "/Looks/Dark", 10.0, translation(0, 0, -1));
    HostValue widths;
    widths.type = OBSCURA_VALUE_FLOAT;
    widths.isArray = true;
    widths.floats = {float(2 * radius)};
    host.addPrim("points", "/Dot",
                 {{"points", HostValue::points({{float(centre[0]), float(centre[1]), float(centre[2])}})},
                  {"widths", widths},
                  {"material:binding", HostValue::path("/Looks/Bright")}});
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
    setBool(host, "taa", false);
    ASSERT_EQ(setInt(host, "msaa", 4), OBSCURA_OK) << host.lastError();
    ASSERT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    const std::vector<float> color = host.readFloats("/Buffers/color");
    // Whether the line of sight through window position (x, y) meets the sphere; nullopt within a
    // thousandth of the radius of its rim.
    auto meets = [&](double x, double y) -> std::optional<bool> {
        const double t = kLitPlaneTanHalfFov;
        const std::array<double, 3> d{(x / kWidth * 2.0 - 1.0) * t, (1.0 - y / kHeight * 2.0) * t, -1.0};
        const std::array<double, 3> o{-centre[0], -centre[1], kLitPlaneCameraDistance - centre[2]};
        const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], od = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
        const double closest = std::sqrt(std::max(0.0, o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - od * od / dd));
        if (std::abs(closest - radius) < 1e-3 * radius) return std::nullopt;
        return closest < radius;
    };
    int edgePixels = 0, checked = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            int covered = 0;
            bool decided = true;
            for (const auto& [sx, sy] : kFourSamples) {
                std::optional<bool> in = meets(x + sx, y + sy);
                if (!in) decided = false;
                covered += in.value_or(false) ? 1 : 0;
            }
            if (!decided) continue;
            ++checked;
            const double coverage = covered / 4.0;
            const double expected = inverseReinhard(coverage * reinhard(bright) + (1.0 - coverage) * reinhard(dark));
            const float measured = color[(size_t(y) * kWidth + x) * 4];
            EXPECT_NEAR(measured, expected, 0.01 * expected + smallFloatStep(float(expected), 6))
                << "pixel " << x << ", " << y << " with " << covered << " samples";
            edgePixels += covered > 0 && covered < 4;
        }
    std::printf("sphere impostor under 4x MSAA: %d pixels checked, %d on its rim\n", checked, edgePixels);
    EXPECT_GT(edgePixels, 40);
    EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
}

TEST(Msaa, MotionBlurAndTransparentsWorkOnTheResolvedGBuffer) {
    // A glowing square moving 8 pixels within the shutter under a white dome, half of it behind a
    // pane of opacity 0.5: the velocity target is multisampled and resolved, the transparents test
    // against the max of the sample depths. Away from edges the image is the one-sample image.
    auto render = [](int32_t msaa, bool& ranEverything) {
        CameraScene s(Lens{}, kWidth, kHeight);
        s.setNumber("shadows", 0);
        s.setNumber("taa", 0);
        s.setShutter(-0.5, 0.5);
        s.host.addPrim("domeLight", "/Sky", {{"inputs:intensity", HostValue::floatValue(1.0f)},
                                             {"inputs:specular", HostValue::floatValue(0.0f)}});
        const double distance = 10.0, unitsPerPixel = distance * (20.955 / 50.0) / kWidth;
        addMaterial(s.host, "/GlowLook", {0, 0, 0}, 1.0f, 0.0f, {1, 1, 1});
        // Edges off the pixel grid (12.3 and 0.4 pixels), so the samples see them.
        addPlane(s.host, "/Glow", "/GlowLook", 12.3 * unitsPerPixel, translation(0, 0, -distance));
        double travel = 8.0 * unitsPerPixel;
        s.host.setTransformMotion("/Glow", -0.5, translation(-0.5 * travel, 0, -distance), 0.5,
                                  translation(0.5 * travel, 0, -distance));
        addMaterial(s.host, "/PaneLook", {0.8f, 0.8f, 0.8f});
        s.host.set("/PaneLook", "inputs:opacity", HostValue::floatValue(0.5f));
        addPlane(s.host, "/Pane", "/PaneLook", 16.0 * unitsPerPixel, translation(-15.6 * unitsPerPixel, 0, -5.0));
        s.setNumber("msaa", msaa);
        image::Image img = s.render();
        ranEverything = ranPass(s.host, "transparent") && ranPass(s.host, "motion_blur_gather_fine") &&
                        (msaa == 1 || ranPass(s.host, "msaa_resolve"));
        return img;
    };
    bool ranOne = false, ranFour = false;
    image::Image one = render(1, ranOne), four = render(4, ranFour);
    EXPECT_TRUE(ranOne && ranFour) << "transparent, motion blur and (with 4 samples) resolve passes";
    image::CompareMetrics m = metrics(four, one);
    std::printf("moving glow behind a pane, motion blur on: msaa 4 vs 1 PSNR %.2f dB SSIM %.4f; streak middle %.3f "
                "vs %.3f, through the pane %.3f vs %.3f\n",
                m.psnr, m.ssim, double(four.at(kWidth / 2 + 4, kHeight / 2, 0)), double(one.at(kWidth / 2 + 4, kHeight / 2, 0)),
                double(four.at(kWidth / 2 - 6, kHeight / 2, 0)), double(one.at(kWidth / 2 - 6, kHeight / 2, 0)));
    EXPECT_GT(m.psnr, 30.0);
    for (int x : {kWidth / 2 + 4, kWidth / 2 - 6})
        EXPECT_NEAR(four.at(x, kHeight / 2, 0), one.at(x, kHeight / 2, 0), 0.02 * one.at(x, kHeight / 2, 0)) << x;
}

TEST(Msaa, RefusesSampleCountsTheDeviceDoesNotOffer) {
    SquareScene s(1.0f);
    ASSERT_EQ(setInt(s.host, "msaa", 4), OBSCURA_OK) << s.host.lastError();  // every Vulkan device offers 4
    for (int32_t samples : {0, 3, 16, -1}) {
        EXPECT_EQ(setInt(s.host, "msaa", samples), OBSCURA_ERROR_INVALID_ARGUMENT) << samples;
        std::string message = s.host.lastError();
        std::printf("msaa=%d: %s\n", samples, message.c_str());
        EXPECT_NE(message.find("msaa"), std::string::npos);
    }
    EXPECT_EQ(setInt(s.host, "msaa", 3), OBSCURA_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(s.host.lastError().find("offers 1"), std::string::npos) << s.host.lastError();
    // A refused count leaves the setting as it was.
    s.renderColor();
    ASSERT_FALSE(s.host.loggedInfos().empty());
    EXPECT_EQ(s.host.loggedInfos().back().rfind("msaa 4x", 0), 0u) << s.host.loggedInfos().back();
}

}  // namespace
}  // namespace obscura::test
