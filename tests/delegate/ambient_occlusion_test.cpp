// SSAO (seed 004: volumetric obscurance, half resolution, bilateral blur) darkens environment
// light in creases, nowhere else, and never across depth discontinuities.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

constexpr float kSky = 1.0f;

// Only a constant dome lights the scene, so rendered radiance = albedo * L * accessibility.
struct DomeScene {
    TestHost host;
    DomeScene() {
        addMaterial(host, "/Looks/Grey", {0.5f, 0.5f, 0.5f});
        host.addPrim("domeLight", "/Sky", {{"inputs:intensity", HostValue::floatValue(kSky)},
                                           {"inputs:specular", HostValue::floatValue(0.0f)}});
        host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
        // Scene units are metres here: the 0.5 m default radius is 0.5 units.
        double metres = 1.0;
        ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &metres};
        host.api().setRenderSetting(host.delegate(), "metersPerUnit", &v);
    }
    void setSsao(bool on) {
        int32_t flag = on ? 1 : 0;
        ObscuraValue v{OBSCURA_VALUE_BOOL, 0, 1, &flag};
        ASSERT_EQ(host.api().setRenderSetting(host.delegate(), "ssao", &v), OBSCURA_OK);
    }
    std::vector<float> render() {
        EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
        EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
        return host.readFloats("/Buffers/color");
    }
};

float green(const std::vector<float>& c, int x, int y) { return c[(size_t(y) * kWidth + x) * 4 + 1]; }

// A floor (y = 0) meeting a wall (z = 0) at a right angle, seen from the front and above.
void addCorner(DomeScene& s) {
    Matrix floor = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 2, 1};  // plane's +Z normal turned to +Y, centred at z = 2
    addPlane(s.host, "/Floor", "/Looks/Grey", 2.0, floor);
    addPlane(s.host, "/Wall", "/Looks/Grey", 2.0, translation(0, 2, 0));
    // Camera at (0, 2, 6) looking down 20 degrees.
    double a = 20.0 * kPi / 180.0;
    s.host.addCamera("/Camera", {1, 0, 0, 0, 0, std::cos(a), -std::sin(a), 0, 0, std::sin(a), std::cos(a), 0, 0, 2, 6, 1});
}

TEST(AmbientOcclusion, CreaseDarkensAndOpenFloorDoesNot) {
    DomeScene s;
    addCorner(s);
    auto occluded = s.render();
    s.setSsao(false);
    auto open = s.render();
    const double unoccluded = 0.5 * kSky;
    // Find the crease row in the centre column: the last wall row above the floor.
    int creaseRow = -1;
    for (int y = 0; y < kHeight; ++y)
        if (std::abs(open[(size_t(y) * kWidth + 32) * 4 + 1] - unoccluded) < 0.02) creaseRow = y;
    ASSERT_GT(creaseRow, 0);
    // Without SSAO every surface pixel has the same radiance.
    for (int y = 0; y < kHeight; ++y) {
        float g = green(open, 32, y);
        if (g > 0) EXPECT_NEAR(g, unoccluded, 0.02) << "row " << y;
    }
    // With SSAO the pixels at the crease are darker than those far from it.
    float nearCrease = green(occluded, 32, kHeight / 2);
    float farFromCrease = green(occluded, 32, kHeight - 2);
    std::printf("accessibility near the crease %.3f, far on the floor %.3f\n", nearCrease / unoccluded,
                farFromCrease / unoccluded);
    float darkest = 1e9f;
    for (int y = 0; y < kHeight; ++y)
        if (green(occluded, 32, y) > 0) darkest = std::min(darkest, green(occluded, 32, y));
    EXPECT_LT(darkest, 0.9 * unoccluded) << "the crease is occluded";
    EXPECT_NEAR(farFromCrease, unoccluded, 0.03 * unoccluded) << "open floor stays unoccluded";
}

TEST(AmbientOcclusion, NoDarkeningAcrossADepthDiscontinuity) {
    DomeScene s;
    s.host.addCamera("/Camera", translation(0, 0, 10));
    addPlane(s.host, "/Back", "/Looks/Grey", 5.0);
    // A small plane 3 units in front of the back plane (6 radii): no occlusion between them.
    addPlane(s.host, "/Front", "/Looks/Grey", 0.6, translation(0, 0, 3));
    auto c = s.render();
    const double unoccluded = 0.5 * kSky;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            float g = green(c, x, y);
            if (g > 0) EXPECT_NEAR(g, unoccluded, 0.03 * unoccluded) << "pixel " << x << ", " << y;
        }
}

// Temporal accumulation (seed 004): renders of an unchanged view accumulate, a moving camera
// reprojects its history, and occlusion that left does not linger.

// Mean absolute second difference along rows in the band of rows [from, to): what a turning sample
// pattern leaves as grain.
double grain(const std::vector<float>& c, int from, int to) {
    double sum = 0;
    int n = 0;
    for (int y = from; y < to; ++y)
        for (int x = 1; x + 1 < kWidth; ++x) {
            float a = green(c, x - 1, y), b = green(c, x, y), d = green(c, x + 1, y);
            if (a > 0 && b > 0 && d > 0) sum += std::fabs(b - 0.5 * (a + d)), ++n;
        }
    return n ? sum / n : 0.0;
}

double meanGreen(const std::vector<float>& c, int from, int to) {
    double sum = 0;
    int n = 0;
    for (int y = from; y < to; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (green(c, x, y) > 0) sum += green(c, x, y), ++n;
    return sum / n;
}

TEST(AmbientOcclusion, StillFramesAccumulateWithoutBias) {
    DomeScene s;
    addCorner(s);
    auto first = s.render();
    std::vector<float> last;
    for (int i = 0; i < 8; ++i) last = s.render();
    const int from = kHeight / 2 - 6, to = kHeight / 2 + 6;  // around the crease
    double before = grain(first, from, to), after = grain(last, from, to);
    double meanBefore = meanGreen(first, from, to), meanAfter = meanGreen(last, from, to);
    std::printf("SSAO temporal accumulation: grain %.5f after 1 frame, %.5f after 9; mean %.4f -> %.4f\n", before,
                after, meanBefore, meanAfter);
    EXPECT_LT(after, before) << "accumulating turned patterns smooths the grain";
    // The first frame is itself one estimate; the turned patterns move the mean by under 2% (measured 1.8%).
    EXPECT_NEAR(meanAfter, meanBefore, 0.03 * meanBefore) << "and does not bias the occlusion";
}

TEST(AmbientOcclusion, RemovedOccluderLeavesNoGhost) {
    DomeScene s;
    s.host.addCamera("/Camera", translation(0, 0, 6));
    addPlane(s.host, "/Floor", "/Looks/Grey", 3.0);
    // A small plane hovering just above the floor darkens the floor around it.
    addPlane(s.host, "/Lid", "/Looks/Grey", 0.5, translation(0, 0, 0.15));
    for (int i = 0; i < 8; ++i) s.render();
    ASSERT_EQ(s.host.api().removePrim(s.host.delegate(), "/Lid"), OBSCURA_OK);
    auto after = s.render();
    const double unoccluded = 0.5 * kSky;
    double worst = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) worst = std::max(worst, std::fabs(green(after, x, y) - unoccluded));
    std::printf("largest departure from unoccluded one frame after the occluder left: %.4f\n", worst / unoccluded);
    EXPECT_LT(worst, 0.03 * unoccluded);
}

TEST(AmbientOcclusion, MovingCameraReprojectsItsHistory) {
    // Renders while the camera slides sideways end close to a fresh render from the last position:
    // the history follows the surfaces instead of smearing them.
    auto cameraAt = [](double x) {
        double a = 20.0 * kPi / 180.0;
        return Matrix{1, 0, 0, 0, 0, std::cos(a), -std::sin(a), 0, 0, std::sin(a), std::cos(a), 0, x, 2, 6, 1};
    };
    DomeScene moving;
    addCorner(moving);
    std::vector<float> last;
    for (int i = 0; i <= 8; ++i) {
        moving.host.setTransform("/Camera", cameraAt(0.05 * i));
        last = moving.render();
    }
    DomeScene fresh;
    addCorner(fresh);
    fresh.host.setTransform("/Camera", cameraAt(0.4));
    auto reference = fresh.render();
    double sum = 0;
    int n = 0;
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p)
        if (reference[p * 4 + 1] > 0) sum += std::fabs(last[p * 4 + 1] - reference[p * 4 + 1]), ++n;
    std::printf("moving camera vs fresh render: mean difference %.4f of the unoccluded radiance\n", sum / n / 0.5);
    EXPECT_LT(sum / n, 0.01 * 0.5 * kSky);
}

}  // namespace
}  // namespace obscura::test
