// Depth of field as a camera integrates it: a still (what `obscura render` makes, taa:frames
// accumulated frames, each looking through its own cell of the aperture and blurred by the
// post-process over that cell alone) converges to the reference's accumulation-buffer lens,
// the diaphragm's shape included; a single real-time frame is the seed's post-process alone.
// Fidelity is the PSNR of x / (1 + x)-mapped linear RGB (mappedPsnr), as against path-traced
// ground truth; every number is printed.
#include "tests/delegate/blur_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace obscura::test {
namespace {

// 16:9, as the ground truth's 640x360, at a quarter of its size.
constexpr int kWidth = 160, kHeight = 90;
constexpr int kReferenceSubFrames = 1024;

const std::array<float, 3> kLight{0.8f, 0.75f, 0.7f}, kDark{0.1f, 0.12f, 0.2f};
const std::array<float, 3> kWarm{0.9f, 0.35f, 0.1f}, kCool{0.1f, 0.45f, 0.85f};

void report(const std::string& what, double psnr) {
    std::printf("%s: %.2f dB\n", what.c_str(), psnr);
    ::testing::Test::RecordProperty(what + " dB", std::to_string(psnr));
}

// A 50 mm lens wide open at f/2.8, focused at 20 units (the default film, 160 pixels wide): CoC
// diameters of 23 pixels on a wall at 60 and 34 on a card at 10 (the thin lens through the field
// of view, DepthOfField tests).
Lens wideOpenLens(int blades) {
    Lens lens;
    lens.fStop = 2.8f;
    lens.focusDistance = 20.0f;
    lens.blades = blades;
    lens.rotationDegrees = 15.0f;
    return lens;
}

// A still with the shutter closed: only the lens is sampled.
struct LensScene : BlurScene {
    explicit LensScene(const Lens& lens) : BlurScene(lens, kWidth, kHeight) {
        setShutter(0.0, 0.0);
        addSky();
    }
    image::Image sharpStill() {
        setNumber("dof", 0);
        image::Image img = render();
        setNumber("dof", 1);
        return img;
    }
};

struct Convergence {
    double still;
    image::Image stillImage, frame, reference;
};

// The still, the single frame and the still without depth of field against the reference; the
// still must come nearer the reference than the single frame does.
Convergence expectStillConverges(LensScene& s, const std::string& what) {
    image::Image frame = s.renderFrame();
    EXPECT_TRUE(ranPass(s.host, "dof_composite"));
    image::Image still = s.render();
    // Every sample of the mean ran the post-process over its cell; the settled frame, none.
    EXPECT_TRUE(s.ranUntilSettled("dof_composite"));
    EXPECT_FALSE(ranPass(s.host, "dof_composite"));
    image::Image reference = s.renderReference(kReferenceSubFrames);
    double stillPsnr = mappedPsnr(still, reference);
    std::printf("%s: still of %d frames\n", what.c_str(), s.stillFrames());
    report(what + ", still vs reference", stillPsnr);
    double framePsnr = mappedPsnr(frame, reference);
    report(what + ", single frame vs reference", framePsnr);
    report(what + ", still without depth of field vs reference", mappedPsnr(s.sharpStill(), reference));
    EXPECT_GT(stillPsnr, framePsnr) << what;
    return {stillPsnr, still, frame, reference};
}

// The planes' still meets the 40 dB. One real-time frame is the seed's post-process over
// the whole aperture, through the lens's centre with no anti-aliasing yet: where depth of field
// blurs (left of the in-focus card, x < 104) it meets the 32 dB; the card's aliased
// chequer edges against the reference's box-filtered ones (27 dB there) are no post-process's
// (TexturedPlanesInOneFrameMatchTheReference holds the whole frame to the bar).
void expectPlanesConverge(LensScene& s, const std::string& what) {
    Convergence c = expectStillConverges(s, what);
    EXPECT_GE(c.still, 40.0) << what;
    double blurred = mappedPsnr(crop(c.frame, 0, 0, 104, kHeight), crop(c.reference, 0, 0, 104, kHeight));
    report(what + ", single frame vs reference where depth of field blurs", blurred);
    EXPECT_GE(blurred, 32.0) << what;
}

// Planes at several depths: a chequered wall far behind the focus plane, a card in focus over the
// right of the image and a chequered card in front of it, lit by a white dome only.
void addPlanes(LensScene& s, Chequer chequer = Chequer::Geometry) {
    s.addChequerCard(chequer, "/Far", {0, 0, -60.0}, 2.0, 24, 14, kLight, kDark);
    s.addChequerCard(chequer, "/InFocus", {3.2, 0, -20.0}, 0.4, 8, 16, kDark, kLight);
    s.addChequerCard(chequer, "/Near", {-1.0, -0.5, -10.0}, 0.35, 4, 4, kWarm, kCool);
}

TEST(DepthOfFieldConvergence, PlanesAtSeveralDepthsMatchTheReference) {
    LensScene s(wideOpenLens(0));
    addPlanes(s);
    expectPlanesConverge(s, "planes, round aperture");
}

// The "textured planes": the same planes with their chequers painted into textures. One
// real-time frame, the seed's post-process over the whole aperture through the lens's centre,
// meets the 32 dB over the whole image: in focus, the texture filter anti-aliases the
// cells' edges where the geometric chequer's alias against the reference's box-filtered pixels.
TEST(DepthOfFieldConvergence, TexturedPlanesInOneFrameMatchTheReference) {
    LensScene s(wideOpenLens(0));
    addPlanes(s, Chequer::Texture);
    image::Image frame = s.renderFrame(), reference = s.renderReference(kReferenceSubFrames);
    double psnr = mappedPsnr(frame, reference);
    report("textured planes, single frame vs reference", psnr);
    report("textured planes, single frame vs reference where depth of field blurs",
           mappedPsnr(crop(frame, 0, 0, 104, kHeight), crop(reference, 0, 0, 104, kHeight)));
    EXPECT_GE(psnr, 32.0);
}

TEST(DepthOfFieldConvergence, PlanesThroughSixBladesMatchTheReference) {
    LensScene s(wideOpenLens(6));
    addPlanes(s);
    expectPlanesConverge(s, "planes, 6 blades");
}

// Strong defocus: rows of small bright emitters (a pixel and a half across, 40 times the
// backdrop's radiance) behind the focus plane and in front of it, over a chequered wall; their
// bokeh are the diaphragm's shape at the CoC. The reference resolves four samples a pixel in each
// sub-frame (renderer::referenceSamples): with one, a point smaller than two pixels was seen
// through one to four pixel centres a sub-frame, and the reference's own noise (41 dB between 1024
// and 4096 sub-frames) was of the bar's size.
void addEmitterRows(LensScene& s, double distance, double y, int count, const std::string& prefix) {
    const double pixel = pinholeUnitsPerPixel(distance, kWidth);
    addMaterial(s.host, prefix + "Look", {0, 0, 0}, 1.0f, 0.0f, {40.0f, 36.0f, 30.0f});
    for (int i = 0; i < count; ++i) {
        double x = (i - 0.5 * (count - 1)) * 0.8 * kWidth / count * pixel;
        std::string path = prefix + std::to_string(i);
        addPlane(s.host, path, prefix + "Look", 0.75 * pixel, translation(x, y * pixel, -distance));
    }
}

void addBokehScene(LensScene& s) {
    addChequerCard(s.host, "/Wall", {0, 0, -80.0}, 3.0, 24, 14, kLight, kDark);
    addEmitterRows(s, 60.0, 20.0, 4, "/FarLight");
    addEmitterRows(s, 11.0, -22.0, 3, "/NearLight");
    addChequerCard(s.host, "/InFocus", {0, 0, -20.0}, 0.3, 6, 3, kDark, kLight);
}

// The still meets the 40 dB.
void expectBokehConverges(LensScene& s, const std::string& what) {
    EXPECT_GE(expectStillConverges(s, what).still, 40.0) << what;
}

TEST(DepthOfFieldConvergence, BokehOfBrightPointsMatchesTheReference) {
    LensScene s(wideOpenLens(0));
    addBokehScene(s);
    expectBokehConverges(s, "bokeh, round aperture");
}

TEST(DepthOfFieldConvergence, HexagonalBokehOfBrightPointsMatchesTheReference) {
    LensScene s(wideOpenLens(6));
    addBokehScene(s);
    expectBokehConverges(s, "bokeh, 6 blades");
}

}  // namespace
}  // namespace obscura::test
