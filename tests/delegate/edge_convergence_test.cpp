// Anti-aliasing as a camera integrates it: a converged still with 4x MSAA is the box-filtered mean
// of radiance over each pixel's square, as the reference's jittered sub-frames are. Thin lines,
// near-horizontal edges and a Siemens star, all emissive over black (no light, so nothing but
// coverage differs), rendered as `obscura render --msaa 4` renders a still. Fidelity is the PSNR of
// x / (1 + x)-mapped linear RGB (mappedPsnr), as against path-traced ground truth.
#include "tests/delegate/blur_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace obscura::test {
namespace {

constexpr int kWidth = 160, kHeight = 90;
constexpr int kReferenceSubFrames = 1024;
constexpr double kDistance = 10.0;

// A flat emissive mesh of triangles in the plane z = -kDistance, given in pixels (x right, y up
// from the image's centre).
void addEmissiveTriangles(TestHost& host, const std::string& path, const std::vector<std::array<double, 2>>& pixels,
                          std::array<float, 3> radiance) {
    const double unit = pinholeUnitsPerPixel(kDistance, kWidth);
    addMaterial(host, path + "Look", {0, 0, 0}, 1.0f, 0.0f, radiance);
    std::vector<std::array<float, 3>> points;
    std::vector<int32_t> counts, indices;
    for (size_t i = 0; i < pixels.size(); ++i) {
        points.push_back({float(pixels[i][0] * unit), float(pixels[i][1] * unit), 0.0f});
        indices.push_back(int32_t(i));
        if (i % 3 == 2) counts.push_back(3);
    }
    host.addPrim("mesh", path,
                 {{"points", HostValue::points(points)},
                  {"faceVertexCounts", HostValue::intArray(counts)},
                  {"faceVertexIndices", HostValue::intArray(indices)},
                  {"subdivisionScheme", HostValue::token("none")},
                  {"doubleSided", HostValue::boolean(true)},
                  {"material:binding", HostValue::path(path + "Look")}},
                 translation(0, 0, -kDistance));
}

// A quad from a centre line (a to b) and a width, as two triangles.
void addStrip(std::vector<std::array<double, 2>>& tris, std::array<double, 2> a, std::array<double, 2> b, double width) {
    double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
    double nx = -dy / len * 0.5 * width, ny = dx / len * 0.5 * width;
    std::array<double, 2> p0{a[0] + nx, a[1] + ny}, p1{a[0] - nx, a[1] - ny}, p2{b[0] - nx, b[1] - ny},
        p3{b[0] + nx, b[1] + ny};
    tris.insert(tris.end(), {p0, p1, p2, p0, p2, p3});
}

void addEdgesScene(TestHost& host) {
    // A Siemens star of 24 spokes, 30 pixels in radius, on the left.
    std::vector<std::array<double, 2>> star;
    constexpr int kSpokes = 24;
    const std::array<double, 2> centre{-40.0, 0.0};
    for (int k = 0; k < kSpokes; ++k) {
        double a0 = 2.0 * kPi * k / kSpokes, a1 = 2.0 * kPi * (k + 0.5) / kSpokes;
        star.insert(star.end(), {centre,
                                 {centre[0] + 30.0 * std::cos(a0), centre[1] + 30.0 * std::sin(a0)},
                                 {centre[0] + 30.0 * std::cos(a1), centre[1] + 30.0 * std::sin(a1)}});
    }
    addEmissiveTriangles(host, "/Star", star, {2.0f, 2.0f, 2.0f});
    // Thin lines, a third of a pixel to a pixel wide, at small angles, on the right.
    std::vector<std::array<double, 2>> lines;
    for (int i = 0; i < 6; ++i) {
        double y = -35.0 + 6.0 * i, width = 0.33 + 0.13 * i, tilt = 0.5 + 1.5 * i;
        addStrip(lines, {5.0, y}, {75.0, y + tilt}, width);
    }
    addEmissiveTriangles(host, "/Lines", lines, {4.0f, 3.0f, 1.0f});
    // A bright card whose top edge is 2 degrees off the horizontal.
    std::vector<std::array<double, 2>> card;
    addStrip(card, {5.0, 20.0}, {75.0, 20.0 + 70.0 * std::tan(2.0 * kPi / 180.0)}, 16.0);
    addEmissiveTriangles(host, "/Card", card, {0.3f, 1.5f, 3.0f});
}

struct EdgesScene : BlurScene {
    EdgesScene() : BlurScene(Lens{}, kWidth, kHeight) {
        setShutter(0.0, 0.0);
        addEdgesScene(host);
    }
};

void report(const std::string& what, double psnr) {
    std::printf("%s: %.2f dB\n", what.c_str(), psnr);
    ::testing::Test::RecordProperty(what + " dB", std::to_string(psnr));
}

// The still's 16 frames x 4 samples fall one in each cell of an 8 x 8 grid over the pixel (each
// sample joining the pixel whose box holds it): 45 dB at least from the reference. The one
// real-time MSAA frame is the floor the still must clear.
TEST(EdgeConvergence, MsaaStillIsThePixelIntegral) {
    EdgesScene s;
    image::Image reference = s.renderReference(kReferenceSubFrames);
    image::Image single = s.render();
    s.setNumber("msaa", 4);
    image::Image frame = s.renderFrame();
    image::Image msaa = s.render();
    std::printf("4x MSAA still of %d frames\n", s.stillFrames());
    double msaaPsnr = mappedPsnr(msaa, reference), framePsnr = mappedPsnr(frame, reference);
    report("edges, 4x MSAA still vs reference", msaaPsnr);
    report("edges, one 4x MSAA frame vs reference", framePsnr);
    report("edges, 1-sample still vs reference", mappedPsnr(single, reference));
    EXPECT_GT(msaaPsnr, framePsnr);
    EXPECT_GE(msaaPsnr, 45.0);
}

// Colour edges inside one surface: a lit card of chequered faces (one mesh, one displayColor per
// face), its cells 3.7 pixels wide so the edges fall anywhere in a pixel. Its samples agree on
// instance, depth and normal, so no pixel is tagged for per-sample lighting: each is lit once, and
// its base colour must be the mean of what its samples saw for the still to be the pixel integral.
TEST(EdgeConvergence, MsaaStillResolvesColourEdgesInsideOneSurface) {
    BlurScene s(Lens{}, kWidth, kHeight);
    s.setShutter(0.0, 0.0);
    s.addSky();
    const double cell = 3.7 * pinholeUnitsPerPixel(kDistance, kWidth);
    addChequerCard(s.host, "/Chequer", {0.3 * cell, 0.2 * cell, -kDistance}, cell, 36, 20, {0.8f, 0.75f, 0.7f},
                   {0.1f, 0.12f, 0.2f});
    image::Image reference = s.renderReference(kReferenceSubFrames);
    s.setNumber("msaa", 4);
    image::Image msaa = s.render();
    const double msaaPsnr = mappedPsnr(msaa, reference);
    report("colour edges inside a surface, 4x MSAA still vs reference", msaaPsnr);
    EXPECT_GE(msaaPsnr, 45.0);
}

// A still through a pixel filter f: behind a straight vertical edge of a glowing half-plane at
// image x = e, the pixel whose centre is c sees the share of the filter beyond the edge, F(c - e),
// F the filter's cumulative distribution (integrated here from the filters' formulas). 64 frames
// put one offset in each 1/64 of the filter's mass along x.
double filterCdf(const std::string& kind, double width, double x) {
    auto f = [&](double v) {
        if (kind == "gaussian") return std::exp(-2.0 * std::pow(v * 6.0 / width, 2));
        if (kind == "blackman-harris") {
            double a = 2.0 * kPi * (v / width + 0.5);
            return 0.35875 - 0.48829 * std::cos(a) + 0.14128 * std::cos(2.0 * a) - 0.01168 * std::cos(3.0 * a);
        }
        return 1.0;
    };
    constexpr int kSteps = 20000;
    double below = 0.0, total = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        double v = ((i + 0.5) / kSteps - 0.5) * width;
        total += f(v);
        if (v < x) below += f(v);
    }
    return below / total;
}

TEST(EdgeConvergence, PixelFilterShapesAStraightEdge) {
    constexpr double kEdge = 80.3;  // image x of the edge, pixels
    for (auto [kind, width] : {std::pair<std::string, double>{"box", 1.0}, {"box", 2.0}, {"gaussian", 3.0},
                               {"blackman-harris", 3.0}}) {
        BlurScene s(Lens{}, kWidth, kHeight);
        s.setShutter(0.0, 0.0);
        setNumber(s.host, "taa:frames", 64);
        setToken(s.host, "pixelFilter", kind);
        setNumber(s.host, "pixelFilter:width", width);
        std::vector<std::array<double, 2>> half;
        addStrip(half, {kEdge - 0.5 * kWidth + 60.0, -60.0}, {kEdge - 0.5 * kWidth + 60.0, 60.0}, 120.0);
        addEmissiveTriangles(s.host, "/Half", half, {1.0f, 1.0f, 1.0f});
        image::Image still = s.render();
        double worst = 0.0;
        for (int x = 70; x < 91; ++x) {
            double expected = filterCdf(kind, width, x + 0.5 - kEdge);
            double measured = still.at(x, kHeight / 2, 1);
            worst = std::max(worst, std::fabs(measured - expected));
            EXPECT_NEAR(measured, expected, 0.02) << kind << " " << width << ", column " << x;
        }
        std::printf("%s of width %.1f: largest difference from the filter's share %.4f\n", kind.c_str(), width, worst);
    }
}

}  // namespace
}  // namespace obscura::test
