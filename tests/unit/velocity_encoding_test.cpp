// The velocity target's format: seed 000 ("An improved reconstruction filter (3)") stores
// velocities in R8G8, gamma 2.0 encoded ("precision still insufficient, but not much noticeable in
// practice"). Its error is measured here over the range motion blur uses, against the half floats
// (RG16F) the G-buffer keeps instead (passes/frame_resources.h kVelocityFormat).
#include "passes/motion_blur.h"

#include <Imath/half.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace obscura {
namespace {

// The slide's encoding of a velocity component normalised to [-1, 1], stored in 8 bits:
// v_enc = sqrt(|v|) sgn(v) 127/255 + 0.5; decoded by inverting it.
float roundTripGamma2(float v) {
    float encoded = std::sqrt(std::fabs(v)) * std::copysign(1.0f, v) * (127.0f / 255.0f) + 0.5f;
    float stored = std::round(std::clamp(encoded, 0.0f, 1.0f) * 255.0f) / 255.0f;
    float d = (stored - 0.5f) * (255.0f / 127.0f);
    return d * d * std::copysign(1.0f, d);
}

TEST(VelocityEncoding, HalfFloatsHoldStreaksFarCloserThanTheSeedsEightBits) {
    // A displacement over the shutter up to twice the longest blur radius (the streak's length)
    // at 1920x1080.
    const double range = 2.0 * passes::motionBlurMaxRadius(1920, 1080);
    double gamma2Max = 0.0, halfMax = 0.0, gamma2AtOnePixel = 0.0;
    const int steps = int(range * 100.0);  // every 0.01 px
    for (int i = 0; i <= steps; ++i) {
        double pixels = range * i / steps;
        double gamma2 = std::fabs(roundTripGamma2(float(pixels / range)) * range - pixels);
        double half = std::fabs(double(float(Imath::half(float(pixels)))) - pixels);
        gamma2Max = std::max(gamma2Max, gamma2);
        halfMax = std::max(halfMax, half);
        if (std::fabs(pixels - 1.0) < 0.02) gamma2AtOnePixel = std::max(gamma2AtOnePixel, gamma2);
    }
    std::printf("velocity error over 0..%.0f px: R8G8 gamma 2.0 %.3f px (%.3f px around 1 px), RG16F %.4f px\n", range,
                gamma2Max, gamma2AtOnePixel, halfMax);
    ::testing::Test::RecordProperty("R8G8 gamma2 max error px", std::to_string(gamma2Max));
    ::testing::Test::RecordProperty("RG16F max error px", std::to_string(halfMax));
    // Half a code step of sqrt(|v|) at the top of the range: 2 x (0.5 / 127) x the range.
    EXPECT_NEAR(gamma2Max, 2.0 * 0.5 / 127.0 * range, 0.05);
    EXPECT_LT(halfMax, 0.05 * gamma2Max);
}

}  // namespace
}  // namespace obscura
