#include "delegate/texture_renormalization.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace obscura::delegate {
namespace {

// d(linear) / d(encoded) of the IEC 61966-2-1 decode at the encoding of `linear`.
float srgbSlopeAt(float linear) {
    if (linear <= 0.0031308f) return 1.0f / 12.92f;
    const float encoded = 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return 2.4f / 1.055f * std::pow((encoded + 0.055f) / 1.055f, 1.4f);
}

}  // namespace

std::optional<Renormalized> renormalize(uint32_t width, uint32_t height, const std::vector<float>& linear,
                                        bool srgbColor) {
    std::array<float, 4> lo, hi;
    lo.fill(std::numeric_limits<float>::max());
    hi.fill(std::numeric_limits<float>::lowest());
    for (size_t i = 0; i < linear.size(); ++i) {
        lo[i % 4] = std::min(lo[i % 4], linear[i]);
        hi[i % 4] = std::max(hi[i % 4], linear[i]);
    }
    Renormalized out;
    for (size_t c = 0; c < 4; ++c) {
        if (srgbColor && c < 3 && hi[c] - lo[c] > srgbSlopeAt(lo[c])) return std::nullopt;
        out.scale[c] = hi[c] - lo[c];
        out.bias[c] = lo[c];
    }
    out.level = {width, height, std::vector<std::byte>(linear.size())};
    for (size_t i = 0; i < linear.size(); ++i) {
        const float range = out.scale[i % 4];
        const float t = range > 0.0f ? (linear[i] - out.bias[i % 4]) / range : 0.0f;
        out.level.bytes[i] = std::byte(static_cast<uint8_t>(std::lround(std::clamp(t, 0.0f, 1.0f) * 255.0f)));
    }
    return out;
}

}  // namespace obscura::delegate
