// Scenes for the motion blur tests: a camera whose shutter is open for one time code around the
// frame, no shadows, and the helpers that render a still as `obscura render` does and measure
// the streak a moving object leaves.
#pragma once

#include "tests/delegate/camera_scene.h"

#include <string>
#include <vector>

namespace obscura::test {

// Scene units per pixel on a plane at `distance` seen through the default 50 mm lens, for an
// image `width` pixels wide.
double pinholeUnitsPerPixel(double distance, int width);

// The shutter open for one frame around the frame's time: [-0.5, 0.5].
struct BlurScene : CameraScene {
    explicit BlurScene(const Lens& lens = Lens{}, int w = 96, int h = 96);
    // A still frame as `obscura render` makes it: temporal AA runs until it reports convergence,
    // so edges are anti-aliased like the reference's jittered sub-frames. With motion blur every
    // frame but the settled last one runs it (the first over the whole shutter, the samples of the
    // mean over their strata); the last keeps the mean, which holds the blur already.
    image::Image render();
    // One real-time frame: the first after a reset, the seed's post-process alone.
    image::Image renderFrame() { return CameraScene::render(); }
    // Whether every frame of the last still ran `pass`, the settled last one aside.
    bool ranUntilSettled(const std::string& pass) const;
    // Whether any frame of the last still ran `pass`.
    bool ranInAnyFrame(const std::string& pass) const;
    int stillFrames() const { return int(stillPasses_.size()); }
    void addSky();
    // A square of `sidePixels` at `distance` glowing white (`radiance`), moving right by
    // `travelPixels` (image x) within the shutter, centred on the view axis at the shutter's centre.
    void addMovingGlow(double sidePixels, double distance, double travelPixels, float radiance = 1.0f);
    // The same square, its transform still and its points moving instead (time samples at the
    // shutter's ends, the host's linear interpolation between them).
    void addDeformingGlow(double sidePixels, double distance, double travelPixels);
    // The still without motion blur.
    image::Image sharp();
    double unitsPerPixel(double distance) const { return pinholeUnitsPerPixel(distance, width); }

private:
    std::vector<std::vector<std::string>> stillPasses_;  // the passes of each frame of the last still
};

float luminance(const image::Image& img, int x, int y);

// The share of pixel column [x, x + 1) a square of `side` pixels covers over the shutter, its
// centre moving from centre - travel / 2 to centre + travel / 2 at a constant speed: the box of the
// pixel swept against the box of the square, integrated numerically.
double sweptCoverage(int x, double centre, double side, double travel);

// The mean of rows [y0, y1) along x.
std::vector<double> rowProfile(const image::Image& img, int y0, int y1);

struct Streak {
    double length;    // pixels from the first to the last above 1/256 (what an 8-bit display shows), inclusive
    double integral;  // sum over the row
    double plateau;   // mean of the middle `plateauWidth` pixels
};

Streak measureStreak(const std::vector<double>& p, int plateauWidth);

}  // namespace obscura::test
