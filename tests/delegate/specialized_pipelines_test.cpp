// The lighting pass is built for the kinds of light a frame holds and the G-buffer for the
// features its draws' materials use (specialization constants: passes/frame_data.h lightKind,
// materialFeatures). A light of a kind the last frame lacked lights the next frame, and one that
// goes leaves the others as they were: a Lambert plane's radiance follows the lights present, each
// against its closed form (render_fixture.h expectRadiance: 1% and one step of the accumulation).
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace obscura::test {
namespace {

constexpr double kSunIrradiance = 3.0;
constexpr double kBulbHeight = 2.0, kBulbRadius = 0.1, kBulbRadiance = 400.0;
constexpr double kDiskHeight = 0.8, kDiskRadius = 0.5, kDiskRadiance = 2.0;
const std::pair<int, int> kPixels[] = {{32, 32}, {10, 20}, {50, 60}};

// The Lambert plane's radiance at the plane point under pixel (x, y) from the lights present.
double expectedRadiance(int x, int y, bool sun, bool bulb, bool disk) {
    auto p = planePointAtPixel(x, y, kLitPlaneCameraDistance, kLitPlaneTanHalfFov);
    double irradiance = sun ? kSunIrradiance : 0.0;
    if (bulb) {
        // A sphere fully above the horizon: E = pi L (r/d)^2 cos(theta).
        double d2 = p[0] * p[0] + p[1] * p[1] + kBulbHeight * kBulbHeight;
        irradiance += kPi * kBulbRadiance * kBulbRadius * kBulbRadius / d2 * (kBulbHeight / std::sqrt(d2));
    }
    if (disk) irradiance += diskIrradiance(kDiskRadiance, kDiskRadius, kDiskHeight, std::hypot(p[0], p[1]));
    return kLitPlaneAlbedo / kPi * irradiance;
}

void expectLights(const std::vector<float>& color, bool sun, bool bulb, bool disk) {
    for (auto [x, y] : kPixels) {
        double l = expectedRadiance(x, y, sun, bulb, disk);
        expectRadiance(color, x, y, {l, l, l});
    }
}

TEST(SpecializedPipelines, LightsOfKindsNewToTheSceneLightItAndThoseThatGoLeaveTheRest) {
    LitPlaneScene s;
    // Each frame whole, without the history of the last one (temporal AA's clamp lets a little of
    // it through after a change: a still accumulates its frames anew).
    setBool(s.host, "taa", false);
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(float(kSunIrradiance))},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   lightPointingAlong({0.0, 0.0, -1.0}));
    {
        SCOPED_TRACE("a distant light (and its cascades) alone");
        expectLights(s.renderColor(), true, false, false);
    }
    s.host.addPrim("sphereLight", "/Bulb",
                   {{"inputs:intensity", HostValue::floatValue(float(kBulbRadiance))},
                    {"inputs:radius", HostValue::floatValue(float(kBulbRadius))},
                    {"inputs:specular", HostValue::floatValue(0.0f)}},
                   translation(0, 0, kBulbHeight));
    {
        SCOPED_TRACE("a sphere light (and its cube map) joins");
        expectLights(s.renderColor(), true, true, false);
    }
    s.host.addPrim("diskLight", "/Disk",
                   {{"inputs:intensity", HostValue::floatValue(float(kDiskRadiance))},
                    {"inputs:radius", HostValue::floatValue(float(kDiskRadius))},
                    {"inputs:specular", HostValue::floatValue(0.0f)},
                    {"inputs:shadow:enable", HostValue::boolean(false)}},
                   translation(0, 0, kDiskHeight));
    {
        SCOPED_TRACE("an unshadowed disk light joins");
        expectLights(s.renderColor(), true, true, true);
    }
    for (const char* light : {"/Sun", "/Bulb"}) {
        s.host.set(light, "visibility", HostValue::token("invisible"));
        ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), light, OBSCURA_DIRTY_VISIBILITY), OBSCURA_OK);
    }
    {
        SCOPED_TRACE("the distant and the sphere light go");
        expectLights(s.renderColor(), false, false, true);
    }
}

}  // namespace
}  // namespace obscura::test
