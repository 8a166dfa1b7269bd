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
        EXPECT_TRUE(host.loggedErrors().empty());
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

}  // namespace
}  // namespace obscura::test
