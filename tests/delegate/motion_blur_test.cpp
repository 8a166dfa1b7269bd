// Motion blur (seed 000 "Motion blur": McGuire et al. 2012's reconstruction filter with the seed's
// improvements) against what the shutter must do and against the renderer's own ground truth: the
// reference mode, which averages sub-frames at times within the shutter. Scenes are lit by a
// white dome only (each cell's radiance is its colour) or glow, so every value is known.
#include "tests/delegate/blur_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace obscura::test {
namespace {

constexpr int kSize = 96;
double unitsPerPixel(double distance) { return pinholeUnitsPerPixel(distance, kSize); }

Matrix rotationZ(double radians, std::array<double, 3> at) {
    Matrix m = translation(at[0], at[1], at[2]);
    double c = std::cos(radians), s = std::sin(radians);
    // Row-vector convention: x' = x c - y s, y' = x s + y c.
    m[0] = c, m[1] = s, m[4] = -s, m[5] = c;
    return m;
}

void expectSimilar(const char* what, const image::CompareMetrics& m, double minPsnr, double minSsim) {
    std::printf("%s: PSNR %.2f dB, SSIM %.4f\n", what, m.psnr, m.ssim);
    ::testing::Test::RecordProperty(std::string(what) + " PSNR dB", std::to_string(m.psnr));
    ::testing::Test::RecordProperty(std::string(what) + " SSIM", std::to_string(m.ssim));
    EXPECT_GT(m.psnr, minPsnr) << what;
    EXPECT_GT(m.ssim, minSsim) << what;
}

// The post-process against the reference, with thresholds set from measurement, and closer to it
// than the frame without motion blur.
void expectCloserThanTheStillFrame(const char* what, const image::Image& post, const image::Image& still,
                                   const image::Image& reference, double minPsnr, double minSsim) {
    image::CompareMetrics none = metrics(still, reference);
    std::printf("%s, without motion blur vs reference: PSNR %.2f dB, SSIM %.4f\n", what, none.psnr, none.ssim);
    image::CompareMetrics blurred = metrics(post, reference);
    expectSimilar((std::string(what) + ", post-process vs reference").c_str(), blurred, minPsnr, minSsim);
    EXPECT_GT(blurred.psnr, none.psnr) << what;
    EXPECT_GT(blurred.ssim, none.ssim) << what;
}

// A glowing square of side S moving L pixels within the shutter: the row through it is the box of
// the square swept by the travel, a trapezoid S + L pixels long with ramps L long, whose middle
// sees the square min(1, S / L) of the time, and whose integral is S (motion blur moves light, it
// does not make or lose it). The length counts the pixels an 8-bit display shows (> 1/256).
struct StreakCase {
    const char* name;
    double side, travel;
    double integralTolerance, plateauTolerance;  // post-process (the reference gets 5% and 0.03)
    double minPsnr, minSsim;                     // post-process vs reference
};

void expectStreak(const StreakCase& c) {
    BlurScene s;
    s.addMovingGlow(c.side, 10.0, c.travel);
    image::Image post = s.render();
    image::Image reference = s.renderReference(96);
    int y0 = kSize / 2 - 4, y1 = kSize / 2 + 4;
    double plateau = std::min(1.0, c.side / c.travel);
    for (auto [what, img] : {std::pair{"post-process", &post}, std::pair{"reference", &reference}}) {
        Streak streak = measureStreak(rowProfile(*img, y0, y1), 8);
        std::printf("%s, %s: streak %.0f px long (predicted %.0f), integral %.2f (predicted %.0f), middle %.3f "
                    "(predicted %.3f)\n",
                    c.name, what, streak.length, c.side + c.travel, streak.integral, c.side, streak.plateau, plateau);
        ::testing::Test::RecordProperty(std::string(c.name) + " " + what + " streak length px",
                                        std::to_string(streak.length));
        bool post = std::string(what) == "post-process";
        EXPECT_NEAR(streak.length, c.side + c.travel, post ? 3.0 : 1.0) << what;
        EXPECT_NEAR(streak.integral, c.side, (post ? c.integralTolerance : 0.05) * c.side) << what;
        EXPECT_NEAR(streak.plateau, plateau, post ? c.plateauTolerance : 0.03) << what;
    }
    expectSimilar((std::string(c.name) + ", post-process vs reference").c_str(), metrics(post, reference), c.minPsnr,
                  c.minSsim);
}

TEST(MotionBlur, TranslatingSquareMakesAStreakOfThePredictedLength) {
    // Measured: 35 px, integral -0.1%, middle 1.000, 42.34 dB, SSIM 0.9965 (before the still
    // sampled the shutter: 34 px, +8.7%, 27.21 dB, SSIM 0.9649, the square's own edge pixels too
    // opaque, see the next test).
    expectStreak({"24 px square moving 12 px", 24.0, 12.0, 0.12, 0.03, 40.0, 0.99});
}

// An object narrower than its travel is seen through in the truth; the reconstruction filter
// (McGuire 2012) has no background behind the object's own pixels, and its weights (the slide's
// DepthCmp and VelCmp: both cones and twice the cylinders for taps on the same surface, one cone
// for the background beside it) keep them mostly opaque: in one frame the streak has the right
// length but too much light in its middle. The still samples the shutter instead (each stratum
// 1.5 px here) and is seen through as the truth is.
TEST(MotionBlur, ThinFastObjectKeepsItsLengthButNotItsTransparency) {
    // Measured: 32 px, integral +1.9%, middle 0.336 against 0.333, 49.25 dB, SSIM 0.9986 (before the
    // still sampled the shutter: 30 px, +47%, middle 0.840, 27.11 dB, SSIM 0.9763).
    expectStreak({"8 px square moving 24 px", 8.0, 24.0, 0.05, 0.03, 45.0, 0.995});
}

// Chequered cards lit by a white dome: a wall far behind and a card in front of its left half.
const std::array<float, 3> kLight{0.8f, 0.75f, 0.7f}, kDark{0.1f, 0.12f, 0.2f};
void addWall(BlurScene& s) {
    s.addSky();
    addChequerCard(s.host, "/Wall", {0, 0, -40.0}, 2.0, 12, 12, kLight, kDark);
}

Matrix rotationY(double radians) {
    Matrix m = identity();
    double c = std::cos(radians), sn = std::sin(radians);
    m[0] = c, m[2] = -sn, m[8] = sn, m[10] = c;
    return m;
}

// The camera turns by 3 degrees (about 12 pixels) and slides sideways within the shutter; the
// scene holds still. Every pixel's velocity is the camera's, reconstructed from depth.
TEST(MotionBlur, PanningCameraMatchesTheReference) {
    BlurScene s;
    addWall(s);
    addChequerCard(s.host, "/Card", {-3.0, 0, -15.0}, 1.0, 4, 6, kDark, kLight);
    constexpr double kTurn = 3.0 * kPi / 180.0;
    s.host.setTransformFunction("/Camera", [](double t) {
        Matrix m = rotationY(kTurn * t);
        m[12] = 0.4 * t;
        return m;
    }, 9);
    image::Image post = s.render();
    image::Image reference = s.renderReference(128);
    // Measured: 32.97 dB, SSIM 0.9816 (before the still sampled the shutter 28.78 dB, 0.9626;
    // without motion blur 17.39 dB, 0.6718).
    expectCloserThanTheStillFrame("panning camera", post, s.sharp(), reference, 31.0, 0.97);
}

// A card rotating by 40 degrees about the view axis within the shutter in front of the wall: its
// far corners sweep arcs, which the filter follows as straight velocities.
TEST(MotionBlur, RotatingObjectMatchesTheReference) {
    BlurScene s;
    addWall(s);
    addChequerCard(s.host, "/Bar", {0, 0, 0}, 0.5, 8, 2, kDark, kLight);
    constexpr double kTurn = 40.0 * kPi / 180.0;
    s.host.setTransformFunction("/Bar", [](double t) { return rotationZ(kTurn * t, {0, 0, -12.0}); }, 9);
    image::Image post = s.render();
    image::Image reference = s.renderReference(128);
    // Measured: 36.28 dB, SSIM 0.9924 (before the still sampled the shutter 26.44 dB, 0.9175;
    // without motion blur 21.57 dB, 0.8796).
    expectCloserThanTheStillFrame("rotating card", post, s.sharp(), reference, 34.0, 0.98);
}

// A deforming mesh (its points move, its transform holds) blurs as the same motion through the
// transform does: the square's points translate within the shutter (time samples at its ends,
// the host's linear interpolation between them), and the image equals the rigid square's.
TEST(MotionBlur, DeformingPointsBlurLikeTheSameMotionThroughTheTransform) {
    constexpr double kSide = 16.0, kTravel = 12.0, kDistance = 10.0;
    BlurScene rigid;
    rigid.addMovingGlow(kSide, kDistance, kTravel);
    image::Image moved = rigid.render();

    BlurScene deforming;
    deforming.addDeformingGlow(kSide, kDistance, kTravel);
    image::Image deformed = deforming.render();
    EXPECT_TRUE(deforming.ranUntilSettled("motion_blur_gather_coarse"));
    image::CompareMetrics same = metrics(deformed, moved);
    Streak streak = measureStreak(rowProfile(deformed, kSize / 2 - 4, kSize / 2 + 4), 4);
    std::printf("deforming square vs the same motion through its transform: PSNR %.2f dB, max error %.4f; streak %.0f px "
                "(predicted %.0f)\n",
                same.psnr, same.maxAbsError, streak.length, kSide + kTravel);
    EXPECT_LT(same.maxAbsError, 0.02);
    EXPECT_NEAR(streak.length, kSide + kTravel, 3.0);
}

// A PointInstancer whose positions are sampled at the shutter's ends moves its instances within
// the shutter: one instance of a glowing square, its position time-sampled, blurs (and
// accumulates in the reference) as the same square moved by its own transform.
TEST(MotionBlur, InstancerPositionsMoveWithinTheShutter) {
    constexpr double kSide = 16.0, kTravel = 12.0, kDistance = 10.0;
    BlurScene rigid;
    rigid.addMovingGlow(kSide, kDistance, kTravel);
    image::Image moved = rigid.render();
    image::Image movedReference = rigid.renderReference(32);

    BlurScene instanced;
    addMaterial(instanced.host, "/GlowLook", {0, 0, 0}, 1.0f, 0.0f, {1, 1, 1});
    addPlane(instanced.host, "/Instancer/Prototypes/Glow", "/GlowLook", 0.5 * kSide * unitsPerPixel(kDistance));
    float t = float(0.5 * kTravel * unitsPerPixel(kDistance));
    instanced.host.addPrim("instancer", "/Instancer",
                           {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Glow"})},
                            {"protoIndices", HostValue::intArray({0})},
                            {"positions", HostValue::points({{0, 0, 0}})}},
                           translation(0, 0, -kDistance));
    instanced.host.setTimeSamples("/Instancer", "positions",
                                  {{-0.5, HostValue::points({{-t, 0, 0}})}, {0.5, HostValue::points({{t, 0, 0}})}});
    image::Image blurred = instanced.render();
    EXPECT_TRUE(instanced.ranUntilSettled("motion_blur_gather_coarse"));
    image::Image reference = instanced.renderReference(32);
    image::CompareMetrics post = metrics(blurred, moved), truth = metrics(reference, movedReference);
    std::printf("instanced square vs the same motion through a transform: motion blur max error %.4f, reference %.4f\n",
                post.maxAbsError, truth.maxAbsError);
    EXPECT_LT(post.maxAbsError, 0.02);
    EXPECT_LT(truth.maxAbsError, 0.02);
}

// USD velocities (UsdGeomPointBased, UsdGeomPointInstancer): points and instances that carry a
// velocity move by it within the shutter, in seconds of timeCodesPerSecond: the same image as the
// same motion through a transform. The shutter here spans one time code (-0.5 .. 0.5), so at 24
// time codes per second a velocity of 24 t units per second moves t units over it.
TEST(MotionBlur, VelocitiesMovePointsAndInstancesWithinTheShutter) {
    constexpr double kSide = 16.0, kTravel = 12.0, kDistance = 10.0;
    BlurScene rigid;
    rigid.addMovingGlow(kSide, kDistance, kTravel);
    image::Image moved = rigid.render();
    const float travel = float(kTravel * unitsPerPixel(kDistance));

    BlurScene mesh;
    mesh.addMovingGlow(kSide, kDistance, 0.0);
    mesh.host.setTransform("/Glow", translation(0, 0, -kDistance));
    // 48 time codes a second: twice the velocity for the same travel.
    mesh.setNumber("timeCodesPerSecond", 48.0);
    std::vector<std::array<float, 3>> velocities(4, {48.0f * travel, 0, 0});
    mesh.host.set("/Glow", "velocities", HostValue::points(velocities));
    image::Image deformed = mesh.render();

    BlurScene instanced;
    addMaterial(instanced.host, "/GlowLook", {0, 0, 0}, 1.0f, 0.0f, {1, 1, 1});
    addPlane(instanced.host, "/Instancer/Prototypes/Glow", "/GlowLook", 0.5 * kSide * unitsPerPixel(kDistance));
    instanced.host.addPrim("instancer", "/Instancer",
                           {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Glow"})},
                            {"protoIndices", HostValue::intArray({0})},
                            {"positions", HostValue::points({{0, 0, 0}})},
                            {"velocities", HostValue::points({{24.0f * travel, 0, 0}})}},
                           translation(0, 0, -kDistance));
    image::Image placed = instanced.render();
    image::CompareMetrics points = metrics(deformed, moved), instances = metrics(placed, moved);
    std::printf("velocities vs the same motion through a transform: mesh points max error %.4f, instances %.4f\n",
                points.maxAbsError, instances.maxAbsError);
    EXPECT_TRUE(mesh.ranUntilSettled("motion_blur_gather_coarse"));
    EXPECT_TRUE(instanced.ranUntilSettled("motion_blur_gather_coarse"));
    EXPECT_LT(points.maxAbsError, 0.02);
    EXPECT_LT(instances.maxAbsError, 0.02);

    // Velocities win over time samples, as in USD: these would move the instance the other way.
    instanced.host.setTimeSamples("/Instancer", "positions",
                                  {{-0.5, HostValue::points({{travel, 0, 0}})}, {0.5, HostValue::points({{-travel, 0, 0}})}});
    ASSERT_EQ(instanced.host.api().markDirty(instanced.host.delegate(), "/Instancer", OBSCURA_DIRTY_POINTS), OBSCURA_OK);
    EXPECT_LT(metrics(instanced.render(), moved).maxAbsError, 0.02);
}

// angularVelocities turn each instance after its orientation (degrees per second about the
// vector, in the instancer's space): the same blur as the orientation time-sampled at the
// shutter's ends. The bar lies along Y after its orientation and turns about X, towards the camera
// (foreshortened); turned before its orientation it would spin about its own length, unseen.
TEST(MotionBlur, AngularVelocitiesTurnInstancesWithinTheShutter) {
    auto scene = [](BlurScene& s) {
        addMaterial(s.host, "/GlowLook", {0, 0, 0}, 1.0f, 0.0f, {1, 1, 1});
        s.host.addPrim("mesh", "/Instancer/Prototypes/Bar",
                       {{"points", HostValue::points({{-0.8f, -0.1f, 0}, {0.8f, -0.1f, 0}, {0.8f, 0.1f, 0}, {-0.8f, 0.1f, 0}})},
                        {"faceVertexCounts", HostValue::intArray({4})},
                        {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                        {"subdivisionScheme", HostValue::token("none")},
                        {"material:binding", HostValue::path("/GlowLook")}});
        const float c = float(std::cos(kPi / 4)), sn = float(std::sin(kPi / 4));  // 90 degrees about Z
        s.host.addPrim("instancer", "/Instancer",
                       {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Bar"})},
                        {"protoIndices", HostValue::intArray({0})},
                        {"positions", HostValue::points({{0, 0, 0}})},
                        {"orientations", HostValue::float4Array({{c, 0, 0, sn}})}},
                       translation(0, 0, -10.0));
    };
    // 120 degrees about X over the shutter's time code, at 24 time codes a second.
    BlurScene turning;
    scene(turning);
    turning.host.set("/Instancer", "angularVelocities", HostValue::points({{120.0f * 24.0f, 0, 0}}));
    image::Image byVelocity = turning.render();
    BlurScene sampled;
    scene(sampled);
    // 90 degrees about Z, then `degrees` about X: the product (turn) x (orientation).
    auto turned = [](double degrees) {
        double a0 = std::cos(0.5 * degrees * kPi / 180.0), a1 = std::sin(0.5 * degrees * kPi / 180.0);
        double q0 = std::cos(kPi / 4), q3 = std::sin(kPi / 4);
        return HostValue::float4Array({{float(a0 * q0), float(a1 * q0), float(-a1 * q3), float(a0 * q3)}});
    };
    sampled.host.setTimeSamples("/Instancer", "orientations", {{-0.5, turned(-60.0)}, {0.0, turned(0.0)}, {0.5, turned(60.0)}});
    image::Image bySamples = sampled.render();
    image::CompareMetrics same = metrics(byVelocity, bySamples);
    std::printf("angular velocity vs the orientation sampled at the shutter's ends: max error %.4f\n", same.maxAbsError);
    EXPECT_TRUE(turning.ranUntilSettled("motion_blur_gather_coarse"));
    EXPECT_LT(same.maxAbsError, 0.02);
}

// A card crossing a still wall: the wall keeps its detail wherever the card's blur cannot reach
// (bit for bit the still frame's), and the card's streak over it matches the reference.
TEST(MotionBlur, MovingObjectLeavesTheStillBackgroundSharp) {
    BlurScene s;
    addWall(s);
    constexpr double kDistance = 12.0, kTravelPixels = 16.0, kHalfSide = 1.0;
    addChequerCard(s.host, "/Card", {0, 0, 0}, 0.5, 4, 4, kDark, kLight);
    double travel = kTravelPixels * unitsPerPixel(kDistance);
    s.host.setTransformMotion("/Card", -0.5, translation(-0.5 * travel, 0, -kDistance), 0.5,
                              translation(0.5 * travel, 0, -kDistance));
    image::Image post = s.render();
    image::Image sharp = s.sharp();
    // The card covers [48 - h, 48 + h) at the shutter's centre, h its half side in pixels; its
    // blur reaches half the travel further each way, and a pixel more for the filtering.
    double h = kHalfSide / unitsPerPixel(kDistance), reach = 0.5 * kTravelPixels + 1.0;
    int outside = 0, changed = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            double dx = std::fabs(x + 0.5 - 48.0), dy = std::fabs(y + 0.5 - 48.0);
            if (dx < h + reach && dy < h + 1.0) continue;
            ++outside;
            for (int c = 0; c < 3; ++c) changed += post.at(x, y, c) != sharp.at(x, y, c) ? 1 : 0;
        }
    std::printf("still background: %d pixels beyond the card's reach, %d channels changed\n", outside, changed);
    EXPECT_EQ(changed, 0);
    // Measured: 35.27 dB, SSIM 0.9717 (before the still sampled the shutter 27.52 dB, 0.9447).
    expectCloserThanTheStillFrame("card over a still wall", post, sharp, s.renderReference(128), 33.0, 0.96);
}

// Both effects at once (seed 000 "MB or DOF first?": depth of field, then motion blur): a card
// in front of the focus plane moving across the defocused wall, against the reference that
// samples the lens and the shutter together.
TEST(MotionBlur, TogetherWithDepthOfFieldMatchesTheReference) {
    Lens lens;
    lens.fStop = 4.0f;
    lens.focusDistance = 20.0f;
    lens.blades = 6;
    BlurScene s(lens);
    addWall(s);
    addChequerCard(s.host, "/InFocus", {3.0, 0, -20.0}, 1.0, 4, 8, kLight, kDark);
    constexpr double kDistance = 12.0;
    addChequerCard(s.host, "/Card", {0, 0, 0}, 0.5, 4, 4, kDark, kLight);
    double travel = 16.0 * unitsPerPixel(kDistance);
    s.host.setTransformMotion("/Card", -0.5, translation(-0.5 * travel, -1.0, -kDistance), 0.5,
                              translation(0.5 * travel, -1.0, -kDistance));
    image::Image post = s.render();
    // Each sample of the still runs both over its strata; the settled frame keeps the mean.
    EXPECT_TRUE(s.ranUntilSettled("dof_gather") && s.ranUntilSettled("motion_blur_gather_coarse"));
    image::Image reference = s.renderReference(256);
    // Measured: 32.40 dB, SSIM 0.9638 since each sample blurs over its own cell of the aperture and
    // a near surface stays wholly in the near field (29.00 dB, 0.9396 with discs of 1/sqrt(N) of
    // the CoC; 26.67 dB, 0.8906 with depth of field on the mean; before the still sampled the
    // shutter 25.59 dB, 0.8814; depth of field alone 24.77 dB, 0.8567).
    expectCloserThanTheStillFrame("depth of field and motion blur", post, s.sharp(), reference, 25.5, 0.88);
}

// USD: a shutter that opens and closes at once has no motion blur; so has the `motionBlur`
// setting off, and a frame where nothing moves: none of the passes run, and the frame is the
// still one exactly.
TEST(MotionBlur, OffWithAClosedShutterTheSettingOffOrNothingMoving) {
    BlurScene s;
    addWall(s);
    image::Image still = s.render();
    EXPECT_FALSE(s.ranInAnyFrame("motion_blur_tile_max")) << "nothing moves";
    s.addMovingGlow(8.0, 10.0, 12.0);
    s.render();
    EXPECT_TRUE(s.ranUntilSettled("motion_blur_tile_max"));
    image::Image off = s.sharp();
    EXPECT_FALSE(s.ranInAnyFrame("motion_blur_tile_max")) << "motionBlur 0";
    s.setShutter(0.0, 0.0);
    image::Image closed = s.render();
    EXPECT_FALSE(s.ranInAnyFrame("motion_blur_tile_max")) << "closed shutter";
    EXPECT_EQ(off.pixels, closed.pixels);
}

// Points whose count changes within the shutter (a sample of another topology at its end) fall
// back to the frame's points there, as USD's ComputePointsAtTime does: the mesh renders unblurred.
TEST(MotionBlur, PointsThatChangeCountWithinTheShutterHoldStill) {
    BlurScene s;
    addWall(s);
    s.addMovingGlow(8.0, 10.0, 0.0);
    image::Image still = s.sharp();
    const float h = float(0.5 * 8.0 * unitsPerPixel(10.0));
    HostValue square = HostValue::points({{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}});
    s.host.setTimeSamples("/Glow", "points", {{0.0, square}, {0.5, HostValue::points({{0, 0, 0}, {1, 0, 0}})}});
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Glow", OBSCURA_DIRTY_POINTS), OBSCURA_OK);
    image::Image img = s.render();
    EXPECT_TRUE(s.host.loggedErrors().empty());
    EXPECT_EQ(renderStats(s.host).primsSkipped, 0u);
    EXPECT_FALSE(s.ranInAnyFrame("motion_blur_tile_max")) << "nothing moves";
    EXPECT_EQ(img.pixels, still.pixels);
}

// The colour AOV's alpha is blurred with the colour: over nothing, a white emitter's streak is as
// transparent as its premultiplied colour is dark (radiance 1: red = alpha), so a compositor gets
// the streak, not the sharp silhouette of the G-buffer's coverage.
TEST(MotionBlur, AlphaIsBlurredWithTheColour) {
    BlurScene s;
    s.addMovingGlow(16.0, 10.0, 12.0);
    s.render();
    std::vector<float> rgba = s.host.readFloats("/Buffers/color");
    float mismatch = 0.0f;
    int partial = 0;
    for (size_t p = 0; p < size_t(kSize) * kSize; ++p) {
        float red = rgba[p * 4], alpha = rgba[p * 4 + 3];
        mismatch = std::max(mismatch, std::fabs(red - alpha));
        partial += alpha > 0.05f && alpha < 0.95f;
    }
    std::printf("motion-blurred white square: %d partly covered pixels, largest |red - alpha| %.4f\n", partial, mismatch);
    EXPECT_GT(partial, 8 * 16) << "the streak's ends: two runs of about 12 pixels on 16 rows";
    EXPECT_LT(mismatch, 0.01f);
}

// The motion AOV: where a surface moves within the shutter, in pixels (x right, y down): the
// square's 12 pixels to the right, the still wall's none; nothing with the setting off.
TEST(MotionBlur, MotionAovHoldsTheDisplacementWithinTheShutter) {
    BlurScene s;
    addWall(s);
    s.addMovingGlow(16.0, 10.0, 12.0);
    s.host.addRenderBuffer("/Buffers/motion", "float32Vec3", kSize, kSize);
    auto motionAt = [&](int x, int y) {
        EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}, {"motion", "/Buffers/motion"}}), OBSCURA_OK)
            << s.host.lastError();
        std::vector<float> m = s.host.readFloats("/Buffers/motion");
        size_t i = (size_t(y) * kSize + size_t(x)) * 3;
        return std::array<float, 3>{m[i], m[i + 1], m[i + 2]};
    };
    auto square = motionAt(kSize / 2, kSize / 2);
    std::printf("motion AOV on the square: (%.3f, %.3f, %.3f) px, predicted (12, 0, 0)\n", square[0], square[1], square[2]);
    EXPECT_NEAR(square[0], 12.0f, 0.05f);
    EXPECT_NEAR(square[1], 0.0f, 0.05f);
    EXPECT_EQ(square[2], 0.0f);
    auto wall = motionAt(4, 4);
    EXPECT_EQ(wall[0], 0.0f);
    EXPECT_EQ(wall[1], 0.0f);
    s.setNumber("motionBlur", 0);
    auto off = motionAt(kSize / 2, kSize / 2);
    EXPECT_EQ(off[0], 0.0f);
    EXPECT_EQ(off[1], 0.0f);
}

// Instancer positions whose count changes at a shutter end (particles born or dying between
// samples) fall back to the frame's, as USD does: the instancer renders, unblurred.
TEST(MotionBlur, InstancerPositionsThatChangeCountWithinTheShutterHoldStill) {
    BlurScene s;
    addWall(s);
    addMaterial(s.host, "/GlowLook", {0, 0, 0}, 1.0f, 0.0f, {1, 1, 1});
    addPlane(s.host, "/Instancer/Prototypes/Glow", "/GlowLook", 0.5);
    s.host.addPrim("instancer", "/Instancer",
                   {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Glow"})},
                    {"protoIndices", HostValue::intArray({0})},
                    {"positions", HostValue::points({{0, 0, 0}})}},
                   translation(0, 0, -10.0));
    s.host.setTimeSamples("/Instancer", "positions",
                          {{0.0, HostValue::points({{0, 0, 0}})}, {0.5, HostValue::points({{0, 0, 0}, {1, 0, 0}})}});
    EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << s.host.lastError();
    EXPECT_TRUE(s.host.loggedErrors().empty());
    EXPECT_EQ(renderStats(s.host).primsSkipped, 0u);
    EXPECT_FALSE(ranPass(s.host, "motion_blur_tile_max")) << "nothing moves";
}

TEST(MotionBlur, BadSettingsAreRefused) {
    BlurScene s;
    for (double samples : {1.0, 33.0, 8.5}) {
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &samples};
        EXPECT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "motionBlur:samples", &v),
                  OBSCURA_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(s.host.lastError().find("motionBlur:samples"), std::string::npos) << s.host.lastError();
    }
    // Velocities are per second: a rate of time codes that is not positive means nothing.
    for (double rate : {0.0, -24.0}) {
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &rate};
        EXPECT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "timeCodesPerSecond", &v),
                  OBSCURA_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(s.host.lastError().find("timeCodesPerSecond"), std::string::npos) << s.host.lastError();
    }
}

// The reference mode samples the shutter for everything that moves. A small sphere light crossing
// above a plane from x = -1 to x = 1 within the shutter: the reference averages its irradiance
// over the path, E = (1/2) int pi L r^2 h / (|p - c(x)|^2)^(3/2) dx (integrated here numerically),
// while the frame itself sees the light at the shutter's centre.
TEST(ReferenceShutter, MovingLightIsAveragedOverItsPath) {
    LitPlaneScene s;
    s.host.set("/Camera", "shutter:open", HostValue::doubleValue(-0.5));
    s.host.set("/Camera", "shutter:close", HostValue::doubleValue(0.5));
    s.host.api().markDirty(s.host.delegate(), "/Camera", OBSCURA_DIRTY_PARAMS);
    constexpr double kRadiance = 400.0, kRadius = 0.05, kHeight = 1.0;
    s.host.addPrim("sphereLight", "/Bulb",
                   {{"inputs:intensity", HostValue::floatValue(float(kRadiance))},
                    {"inputs:radius", HostValue::floatValue(float(kRadius))},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   translation(0, 0, kHeight));
    s.host.setTransformMotion("/Bulb", -0.5, translation(-1.0, 0, kHeight), 0.5, translation(1.0, 0, kHeight));
    auto irradianceFrom = [&](const std::array<double, 3>& p, double lightX) {
        double dx = p[0] - lightX, d2 = dx * dx + p[1] * p[1] + kHeight * kHeight;
        return kPi * kRadiance * kRadius * kRadius / d2 * (kHeight / std::sqrt(d2));
    };
    for (auto [x, y] : {std::pair{32, 32}, std::pair{12, 40}}) {
        auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
        double average = 0.0;
        constexpr int kSteps = 4000;
        for (int i = 0; i < kSteps; ++i) average += irradianceFrom(p, -1.0 + 2.0 * (i + 0.5) / kSteps) / kSteps;
        double centre = irradianceFrom(p, 0.0);
        std::printf("pixel (%d, %d): irradiance averaged over the light's path %.4f, at the shutter's centre %.4f\n", x,
                    y, average, centre);
        double l = kLitPlaneAlbedo / kPi;
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, nullptr};
        double subFrames = 128;
        v.data = &subFrames;
        ASSERT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "reference", &v), OBSCURA_OK);
        expectRadiance(s.renderColor(), x, y, {l * average, l * average, l * average});
        double off = 0;
        v.data = &off;
        ASSERT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "reference", &v), OBSCURA_OK);
        expectRadiance(s.renderColor(), x, y, {l * centre, l * centre, l * centre});
    }
}

// Deforming points in the reference: the square whose points translate accumulates as the same
// motion through its transform does.
TEST(ReferenceShutter, DeformingPointsMoveInTheSubFrames) {
    constexpr double kSide = 16.0, kTravel = 12.0, kDistance = 10.0;
    BlurScene rigid;
    rigid.addMovingGlow(kSide, kDistance, kTravel);
    image::Image moved = rigid.renderReference(32);
    BlurScene deforming;
    deforming.addDeformingGlow(kSide, kDistance, kTravel);
    image::Image deformed = deforming.renderReference(32);
    image::CompareMetrics same = metrics(deformed, moved);
    std::printf("reference: deforming square vs the same motion through its transform: max error %.4f\n",
                same.maxAbsError);
    EXPECT_LT(same.maxAbsError, 0.02);
    Streak streak = measureStreak(rowProfile(deformed, kSize / 2 - 4, kSize / 2 + 4), 4);
    EXPECT_NEAR(streak.length, kSide + kTravel, 1.0);
}

}  // namespace
}  // namespace obscura::test
