// The lens of depth of field (pass_support/thin_lens.h): the CoC against Potmesil's formula seen
// through USD's field of view, the concentric mapping and the diaphragm's polygon, and the
// reference mode's sub-frames and a still's cells of the aperture (renderer/reference_frames.h).
#include "renderer/reference_frames.h"
#include "pass_support/thin_lens.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <numbers>

namespace obscura::passes {
namespace {

constexpr double kPi = std::numbers::pi;

// An 85 mm f/2 lens focused at 3 m on a 36 mm film, in centimetres (USD's default stage unit).
ThinLens portraitLens() { return {8.5, 2.0, 300.0, 3.6}; }

// Potmesil & Chakravarty 1981, written out as in seed 000 "Lens review (2)": the image distance of
// each point from the thin-lens equation 1/P + 1/I = 1/F, then similar triangles through the
// aperture A = F / f.
double potmesilCoc(const ThinLens& lens, double distance) {
    double F = lens.focalLength, P = lens.focusDistance, D = distance, A = F / lens.fStop;
    double focusImage = F * P / (P - F), pointImage = F * D / (D - F);
    return A * std::fabs(pointImage - focusImage) / pointImage;
}

// Device depth of a distance for a perspective projection with these clipping planes (Vulkan,
// depth 0 at near): 1/D is affine in depth.
double deviceDepth(double distance, double nearClip, double farClip) {
    return (1.0 / distance - 1.0 / nearClip) / (1.0 / farClip - 1.0 / nearClip);
}

// Potmesil's CoC lies on a film at the image distance I = F P / (P - F); USD's field of view is the
// focal length's (no focus breathing), so the image's film lies at F, where the same cone of light
// is F / I as wide.
double cocOnTheFilmAtF(const ThinLens& lens, double distance) {
    double F = lens.focalLength, P = lens.focusDistance;
    return potmesilCoc(lens, distance) * F / (F * P / (P - F));
}

TEST(ThinLens, CocIsPotmesilsFormulaOnTheFilmOfTheFieldOfView) {
    ThinLens lens = portraitLens();
    for (double D : {50.0, 150.0, 299.0, 301.0, 600.0, 5000.0}) {
        double F = lens.focalLength, P = lens.focusDistance, f = lens.fStop;
        double slide = std::fabs(F * D / (D - F) - F * P / (P - F)) * (D - F) / (f * D);
        double simplified = std::fabs((F / f) * F * (P - D) / (D * (P - F)));
        EXPECT_NEAR(circleOfConfusionDiameter(lens, D), cocOnTheFilmAtF(lens, D), 1e-12) << D;
        EXPECT_NEAR(slide, potmesilCoc(lens, D), 1e-12) << D;
        EXPECT_NEAR(simplified, potmesilCoc(lens, D), 1e-12) << D;
    }
    EXPECT_NEAR(circleOfConfusionDiameter(lens, lens.focusDistance), 0.0, 1e-12);
}

TEST(ThinLens, OneMultiplyAddOnDepthGivesTheSignedCocInPixels) {
    ThinLens lens = portraitLens();
    const double nearClip = 10.0, farClip = 10000.0, width = 1920.0;
    CocFromDepth coc = cocFromDepth(lens, nearClip, farClip, width);
    for (double D : {20.0, 100.0, 250.0, 300.0, 350.0, 900.0, 9000.0}) {
        double expected = cocOnTheFilmAtF(lens, D) / lens.filmWidth * width / 2.0 * (D < lens.focusDistance ? 1.0 : -1.0);
        EXPECT_NEAR(coc.radiusPixels(deviceDepth(D, nearClip, farClip)), expected, 1e-9 * width) << D;
    }
    double D = 900.0;
    std::printf("85 mm f/2 focused at 3 m, 36 mm film, 1920 px: CoC at 9 m %.3f mm = %.2f px diameter\n",
                10.0 * cocOnTheFilmAtF(lens, D), -2.0 * coc.radiusPixels(deviceDepth(D, nearClip, farClip)));
}

TEST(ThinLens, NoDepthOfFieldWithoutFStopOrFocusBeyondTheFocalLength) {
    ThinLens lens = portraitLens();
    EXPECT_TRUE(hasDepthOfField(lens));
    lens.fStop = 0.0;  // USD: no depth of field
    EXPECT_FALSE(hasDepthOfField(lens));
    CocFromDepth none = cocFromDepth(lens, 1.0, 100.0, 64.0);
    EXPECT_EQ(none.scale, 0.0);
    EXPECT_EQ(none.bias, 0.0);
    lens = portraitLens();
    lens.focusDistance = 0.0;  // USD's default
    EXPECT_FALSE(hasDepthOfField(lens));
    lens.focusDistance = lens.focalLength;
    EXPECT_FALSE(hasDepthOfField(lens));
}

// An accumulation camera's pinholes shift a point at D by a F (1/D - 1/P) on a film at F; with the
// aperture from accumulationApertureDiameter that blur is the CoC.
TEST(ThinLens, AccumulationCameraBlursByTheThinLensCoc) {
    ThinLens lens = portraitLens();
    double a = accumulationApertureDiameter(lens);
    for (double D : {50.0, 200.0, 900.0, 9000.0})
        EXPECT_NEAR(a * lens.focalLength * std::fabs(1.0 / D - 1.0 / lens.focusDistance), cocOnTheFilmAtF(lens, D),
                    1e-12)
            << D;
    lens.fStop = 0.0;
    EXPECT_EQ(accumulationApertureDiameter(lens), 0.0) << "a pinhole";
}

TEST(Aperture, BladesOrACircle) {
    EXPECT_EQ(apertureShape(6, 0).blades, 6);
    EXPECT_EQ(apertureShape(0, 30).blades, 0) << "no blades: round";
    EXPECT_EQ(apertureShape(2, 30).blades, 0) << "two blades make no polygon";
    EXPECT_NEAR(apertureShape(5, 90).rotation, kPi / 2.0, 1e-12);
}

// Evenly spread square points on the aperture (the gather's taps): cell centres of a fine grid.
template <typename Visit>
void forEachGridSample(int side, const ApertureShape& shape, Visit visit) {
    for (int i = 0; i < side * side; ++i) visit(sampleAperture(squareGridCell(i, side), shape));
}

TEST(Aperture, ConcentricMappingIsUniformOnTheDisc) {
    // Uniform on the unit disc: E[r^2] = 1/2, each quadrant a quarter, nothing outside.
    double meanSquare = 0.0, quadrant = 0.0;
    const int side = 200;
    forEachGridSample(side, {}, [&](const std::array<double, 2>& p) {
        double r2 = p[0] * p[0] + p[1] * p[1];
        EXPECT_LE(r2, 1.0 + 1e-12);
        meanSquare += r2 / (side * side);
        if (p[0] > 0 && p[1] > 0) quadrant += 1.0 / (side * side);
    });
    EXPECT_NEAR(meanSquare, 0.5, 1e-3);
    EXPECT_NEAR(quadrant, 0.25, 1e-3);
}

// Radius of the regular polygon inscribed in the unit circle along `angle` (middle of an edge at
// `rotation`).
double polygonBoundary(double angle, int blades, double rotation) {
    double sector = 2.0 * kPi / blades, local = std::remainder(angle - rotation, sector);
    return std::cos(kPi / blades) / std::cos(local);
}

TEST(Aperture, TheSamplesFillTheRotatedPolygon) {
    for (int blades : {5, 6, 9}) {
        ApertureShape shape = apertureShape(blades, 20.0);
        constexpr int kBins = 360;
        std::vector<double> reach(kBins, 0.0);
        forEachGridSample(300, shape, [&](const std::array<double, 2>& p) {
            double r = std::hypot(p[0], p[1]);
            double angle = std::atan2(p[1], p[0]);
            EXPECT_LE(r, polygonBoundary(angle, blades, shape.rotation) + 1e-9) << "inside the polygon";
            int bin = int(std::floor((angle + kPi) / (2.0 * kPi) * kBins)) % kBins;
            reach[size_t(bin)] = std::max(reach[size_t(bin)], r);
        });
        for (int bin = 0; bin < kBins; ++bin) {
            double angle = (bin + 0.5) / kBins * 2.0 * kPi - kPi;
            EXPECT_NEAR(reach[size_t(bin)], polygonBoundary(angle, blades, shape.rotation), 0.02)
                << blades << " blades, " << angle * 180.0 / kPi << " degrees";
        }
    }
}

TEST(Aperture, EvenSquarePointsCoverThePolygonEvenly) {
    // The share of samples in each cell of a coarse grid equals the share of the polygon's area
    // there (counted on a fine grid of points): a flat bokeh.
    ApertureShape shape = apertureShape(6, 10.0);
    constexpr int kCells = 6;
    auto cellOf = [](double x, double y) {
        int cx = std::clamp(int((x + 1.0) / 2.0 * kCells), 0, kCells - 1);
        int cy = std::clamp(int((y + 1.0) / 2.0 * kCells), 0, kCells - 1);
        return size_t(cy * kCells + cx);
    };
    std::vector<double> weighted(kCells * kCells, 0.0), area(kCells * kCells, 0.0);
    double totalWeight = 0.0, totalArea = 0.0;
    forEachGridSample(400, shape, [&](const std::array<double, 2>& p) {
        weighted[cellOf(p[0], p[1])] += 1.0;
        totalWeight += 1.0;
    });
    const int fine = 800;
    for (int j = 0; j < fine; ++j)
        for (int i = 0; i < fine; ++i) {
            double x = (2.0 * i + 1.0) / fine - 1.0, y = (2.0 * j + 1.0) / fine - 1.0;
            if (std::hypot(x, y) <= polygonBoundary(std::atan2(y, x), shape.blades, shape.rotation))
                area[cellOf(x, y)] += 1.0, totalArea += 1.0;
        }
    double worst = 0.0;
    for (size_t c = 0; c < area.size(); ++c) worst = std::max(worst, std::fabs(weighted[c] / totalWeight - area[c] / totalArea));
    std::printf("largest difference of a cell's weighted sample share from its area share: %.5f\n", worst);
    EXPECT_LT(worst, 2e-3);
}

}  // namespace
}  // namespace obscura::passes

namespace obscura::renderer {
namespace {

TEST(ReferenceSubFrames, StratifiedOverTheApertureShutterAndPixel) {
    passes::ApertureShape shape = passes::apertureShape(5, 0.0);
    const uint32_t count = 256;
    std::vector<ReferenceSubFrame> frames = referenceSubFrames(count, shape);
    ASSERT_EQ(frames.size(), count);
    double weight = 0.0, cx = 0.0, cy = 0.0;
    std::vector<int> shutterStrata(16, 0), jitterStrata(16, 0);
    for (const auto& f : frames) {
        EXPECT_LE(std::hypot(f.aperture[0], f.aperture[1]), 1.0 + 1e-12);
        ASSERT_GE(f.shutter, 0.0);
        ASSERT_LT(f.shutter, 1.0);
        ASSERT_GE(f.pixelJitter[0], -0.5);
        ASSERT_LT(f.pixelJitter[0], 0.5);
        ++shutterStrata[size_t(f.shutter * 16)];
        ++jitterStrata[size_t((f.pixelJitter[0] + 0.5) * 4) * 4 + size_t((f.pixelJitter[1] + 0.5) * 4)];
        weight += 1.0;
        cx += f.aperture[0];
        cy += f.aperture[1];
    }
    EXPECT_NEAR(cx / weight, 0.0, 0.01) << "the lens samples centre on the axis";
    EXPECT_NEAR(cy / weight, 0.0, 0.01);
    for (int n : shutterStrata) EXPECT_EQ(n, 16) << "every sixteenth of the shutter gets its share";
    std::vector<ReferenceSubFrame> odd = referenceSubFrames(100, shape);
    std::vector<int> hundredths(100, 0);
    for (const auto& f : odd) ++hundredths[size_t(f.shutter * 100)];
    for (int n : hundredths) EXPECT_EQ(n, 1) << "any count: one sub-frame per 1/N of the shutter";
    // Halton points in bases 3 and 5 are stratified exactly only at powers of those bases.
    for (int n : jitterStrata) EXPECT_NEAR(n, 16, 5) << "every sixteenth of the pixel gets about its share";
}

// A still's frames look through cells of the aperture that partition it: every point of the
// square before the mapping lies in exactly one of the cells, each frame looks from its cell
// centre's point, and each cell is visited by two frames of an even count (frames 2c and 2c + 1)
// and by one of an odd count, for counts that are squares, rectangles and primes.
TEST(StillLensSamples, CellsPartitionTheAperture) {
    for (int blades : {0, 6})
        for (uint32_t count : {16u, 8u, 7u, 1u}) {
            passes::ApertureShape shape = passes::apertureShape(blades, 15.0);
            const uint32_t visits = count % 2 == 0 ? 2 : 1;
            EXPECT_EQ(stillLensCells(count), count / visits);
            constexpr int kFine = 64;
            std::vector<int> owners(kFine * kFine, 0);
            std::map<std::pair<long, long>, std::vector<uint32_t>> framesOfCell;
            for (uint32_t k = 0; k < count; ++k) {
                StillLensSample s = stillLensSample(k, count, shape);
                EXPECT_NEAR(s.cell.share(), 1.0 / std::sqrt(double(count / visits)), 1e-12);
                auto expected = passes::sampleAperture(s.cell.centre, shape);
                EXPECT_EQ(s.position, expected) << "the frame looks from its cell's centre";
                framesOfCell[{std::lround(s.cell.centre[0] * 1e6), std::lround(s.cell.centre[1] * 1e6)}].push_back(k);
                for (int j = 0; j < kFine; ++j)
                    for (int i = 0; i < kFine; ++i) {
                        double x = (2.0 * i + 1.0) / kFine - 1.0, y = (2.0 * j + 1.0) / kFine - 1.0;
                        if (std::fabs(x - s.cell.centre[0]) < s.cell.halfSize[0] &&
                            std::fabs(y - s.cell.centre[1]) < s.cell.halfSize[1])
                            ++owners[size_t(j * kFine + i)];
                    }
            }
            EXPECT_EQ(framesOfCell.size(), count / visits) << "every cell";
            for (const auto& [cell, frames] : framesOfCell) {
                ASSERT_EQ(frames.size(), visits) << count << " frames";
                if (visits == 2) EXPECT_EQ(frames[1], frames[0] + 1) << "frames 2c and 2c + 1";
            }
            for (int n : owners) ASSERT_EQ(n, int(visits)) << count << " frames: each point of the square in " << visits;
        }
}

// A still's MSAA frames under the box filter: Vulkan's standard 4-sample locations shifted by the
// 16 frames' jitters and wrapped around the pixel's box fall one in each cell of an 8 x 8 grid.
TEST(PixelBoxJitter, SixteenFramesOfFourSamplesFillAnEightByEightGrid) {
    const double locations[4][2] = {{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};
    constexpr uint32_t kFrames = 16;
    std::vector<int> cells(64, 0);
    for (uint32_t k = 0; k < kFrames; ++k) {
        auto [jx, jy] = pixelBoxJitter(k, kFrames, 4);
        EXPECT_LT(std::fabs(jx), 0.125 + 1e-12) << "within a strip a quarter of the pixel wide";
        EXPECT_LT(std::fabs(jy), 0.5);
        for (const auto& l : locations) {
            // The image moves by the jitter: the sample sees what lies at its location minus it.
            double x = l[0] - jx, y = l[1] - jy;
            x -= std::floor(x);
            y -= std::floor(y);
            ++cells[size_t(int(y * 8.0) * 8 + int(x * 8.0))];
        }
    }
    for (int n : cells) EXPECT_EQ(n, 1);
}

// The reference's sub-frames take four samples a pixel under the box filter of width 1 (one under
// any other), each jittered within its own column of the pixel: the standard 4-sample locations,
// shifted by 1024 sub-frames' jitters and wrapped around the box, fall evenly over a 16 x 16 grid
// of the pixel (each cell about its share: Halton points in bases 3 and 5 are stratified exactly
// only at powers of those bases).
TEST(ReferenceSubFrames, FourSamplesSweepThePixelEvenlyUnderTheBox) {
    EXPECT_EQ(referenceSamples({}), 4u);
    EXPECT_EQ(referenceSamples({PixelFilterKind::Box, 2.0}), 1u);
    EXPECT_EQ(referenceSamples({PixelFilterKind::Gaussian, 1.0}), 1u);
    const double locations[4][2] = {{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};
    constexpr uint32_t kCount = 1024;
    std::vector<int> cells(256, 0);
    for (const ReferenceSubFrame& f : referenceSubFrames(kCount, {}, {}, 4)) {
        EXPECT_LT(std::fabs(f.pixelJitter[0]), 0.125 + 1e-12) << "within a strip a quarter of the pixel wide";
        EXPECT_LT(std::fabs(f.pixelJitter[1]), 0.5 + 1e-12);
        for (const auto& l : locations) {
            double x = l[0] - f.pixelJitter[0], y = l[1] - f.pixelJitter[1];
            x -= std::floor(x);
            y -= std::floor(y);
            ++cells[size_t(int(y * 16.0) * 16 + int(x * 16.0))];
        }
    }
    for (int n : cells) EXPECT_NEAR(n, 16, 5);
}

// A kernel over a cell reaches as far as the cell's farthest point from its centre's: the unit
// circle's radius for the whole aperture; for a quarter of the square, its mapped quarter disc.
TEST(StillLensSamples, CellReach) {
    EXPECT_NEAR(passes::apertureCellReach({}, {}), 1.0, 1e-9);
    EXPECT_NEAR(passes::apertureCellReach({}, passes::apertureShape(6, 15.0)), 1.0, 1e-9);
    // [0, 1]^2 maps to the quarter disc between 0 and 90 degrees; its centre (0.5, 0.5) to radius
    // 0.5 at 45 degrees, whose farthest points are the arc's ends at radius 1 (0 and 90 degrees).
    passes::ApertureCell quarter{{0.5, 0.5}, {0.5, 0.5}};
    double far = std::hypot(1.0 - 0.5 * std::cos(std::numbers::pi / 4.0), 0.5 * std::sin(std::numbers::pi / 4.0));
    EXPECT_NEAR(passes::apertureCellReach(quarter, {}), far, 1e-9);
}

}  // namespace
}  // namespace obscura::renderer
