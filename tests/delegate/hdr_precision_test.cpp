// Seed 004 "HDR": the light accumulation in B10G11R11_UFLOAT against RGBA16F on a lit scene with a
// smooth gradient, a colour and a specular highlight. The small float keeps 6 (R, G) and 5 (B)
// mantissa bits, so its relative error is below 2^-6 and 2^-5 per channel (plus RGBA16F's own
// 2^-11); printed: the measured errors and how many display (8-bit, view-transformed) codes move.
#include "tests/delegate/render_fixture.h"

#include <cmath>

namespace obscura::test {
namespace {

struct Frame {
    std::vector<float> color;
    std::vector<uint8_t> display;
};

Frame renderWith(bool halfFloat) {
    LitPlaneScene s;
    addMaterial(s.host, "/Looks/Glossy", {0.8f, 0.35f, 0.1f}, 0.3f);
    s.host.set("/Plane", "material:binding", HostValue::path("/Looks/Glossy"));
    s.host.addPrim("sphereLight", "/Bulb",
                   {{"inputs:intensity", HostValue::floatValue(60.0f)}, {"inputs:radius", HostValue::floatValue(0.1f)}},
                   translation(0.3, 0.2, 1.0));
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(0.7f)},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:color", HostValue::float3(0.6f, 0.7f, 1.0f)}},
                   lightPointingAlong({0.4, -0.3, -1}));
    s.host.addRenderBuffer("/Buffers/display", "unorm8Vec4", kWidth, kHeight);
    // Frames of temporal AA 1TX (a still's) accumulate in half floats whatever the setting:
    // measure a frame without temporal AA.
    setBool(s.host, "taa", false);
    int32_t on = halfFloat ? 1 : 0;
    ObscuraValue v{OBSCURA_VALUE_BOOL, 0, 1, &on};
    EXPECT_EQ(s.host.api().setRenderSetting(s.host.delegate(), "lighting:halfFloat", &v), OBSCURA_OK);
    EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}, {"display", "/Buffers/display"}}), OBSCURA_OK)
        << s.host.lastError();
    Frame f{s.host.readFloats("/Buffers/color"), {}};
    ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
    EXPECT_EQ(s.host.api().mapRenderBuffer(s.host.delegate(), "/Buffers/display", &m), OBSCURA_OK);
    const auto* bytes = static_cast<const uint8_t*>(m.data);
    f.display.assign(bytes, bytes + size_t(kWidth) * kHeight * 4);
    s.host.api().unmapRenderBuffer(s.host.delegate(), "/Buffers/display");
    return f;
}

TEST(HdrPrecision, SmallFloatAccumulationStaysWithinItsMantissa) {
    Frame small = renderWith(false), half = renderWith(true);
    const double bound[3] = {std::ldexp(1.0, -6), std::ldexp(1.0, -6), std::ldexp(1.0, -5)};
    double maxError[3] = {}, sumError[3] = {};
    int counted = 0, codesMoved = 0, largestMove = 0;
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) {
        for (int c = 0; c < 3; ++c) {
            double reference = half.color[p * 4 + c];
            ASSERT_GT(reference, 1e-3) << "the scene lights every pixel";
            double error = std::fabs(small.color[p * 4 + c] - reference) / reference;
            EXPECT_LE(error, bound[c] + std::ldexp(1.0, -10)) << "pixel " << p << " channel " << c;
            maxError[c] = std::max(maxError[c], error);
            sumError[c] += error;
            int move = std::abs(int(small.display[p * 4 + c]) - int(half.display[p * 4 + c]));
            codesMoved += move > 0;
            largestMove = std::max(largestMove, move);
        }
        ++counted;
    }
    // Truncation or rounding of a 6-bit mantissa is visible after an 8-bit view transform only
    // by a code or two.
    EXPECT_LE(largestMove, 3);
    std::printf("B10G11R11 vs RGBA16F: relative error mean %.4f%% / %.4f%% / %.4f%%, max %.3f%% / %.3f%% / %.3f%% "
                "(R/G/B); display codes changed on %.1f%% of channels, by at most %d\n",
                100 * sumError[0] / counted, 100 * sumError[1] / counted, 100 * sumError[2] / counted,
                100 * maxError[0], 100 * maxError[1], 100 * maxError[2], 100.0 * codesMoved / (3 * counted),
                largestMove);
}

// A converged still of a glossy plane under a distant light of irradiance `irradiance`.
std::vector<float> stillUnder(float irradiance) {
    LitPlaneScene s;
    addMaterial(s.host, "/Looks/Glossy", {0.8f, 0.35f, 0.1f}, 0.3f);
    s.host.set("/Plane", "material:binding", HostValue::path("/Looks/Glossy"));
    s.host.addPrim("distantLight", "/Sun",
                   {{"inputs:intensity", HostValue::floatValue(irradiance)},
                    {"inputs:normalize", HostValue::boolean(true)},
                    {"inputs:color", HostValue::float3(0.6f, 0.7f, 1.0f)}},
                   lightPointingAlong({0.4, -0.3, -1}));
    for (int frame = 0; frame < 32; ++frame) {
        EXPECT_EQ(s.host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << s.host.lastError();
        if (renderStats(s.host).converged) break;
    }
    EXPECT_TRUE(renderStats(s.host).converged);
    return s.host.readFloats("/Buffers/color");
}

TEST(HdrPrecision, DimScenesAreTheBrightOnesScaled) {
    // The same still under a light 2^20 times dimmer (an unnormalised sun's irradiance is of that
    // order): its radiances, around 1e-7, are below half floats' normal range (2^-14), where the
    // light accumulation and the still's mean would keep a few bits of them. The accumulation is
    // pre-exposed by a power of two instead (CameraData::outputScale), so the dim image is the
    // bright one scaled, to the bit.
    const float bright = 0.75f, dim = std::ldexp(bright, -20);
    std::vector<float> brightImage = stillUnder(bright), dimImage = stillUnder(dim);
    ASSERT_EQ(brightImage.size(), dimImage.size());
    double worst = 0.0;
    for (size_t i = 0; i < brightImage.size(); ++i) {
        if (i % 4 == 3) continue;  // coverage
        ASSERT_GT(brightImage[i], 1e-3f) << "the light reaches every pixel";
        worst = std::max(worst, std::fabs(std::ldexp(double(dimImage[i]), 20) - brightImage[i]) / brightImage[i]);
    }
    std::printf("[ metric ] still under a sun 2^20 times dimmer, scaled back: worst relative difference %.3g\n", worst);
    EXPECT_EQ(worst, 0.0);
}

}  // namespace
}  // namespace obscura::test
