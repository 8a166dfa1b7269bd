#include "harness/texture_coordinates.h"

#include <cmath>
#include <numbers>

namespace obscura::harness {

StTransform compose(const StTransform& outer, const StTransform& inner) {
    auto row = [&](const std::array<double, 3>& o) {
        return std::array<double, 3>{o[0] * inner.s[0] + o[1] * inner.t[0], o[0] * inner.s[1] + o[1] * inner.t[1],
                                     o[0] * inner.s[2] + o[1] * inner.t[2] + o[2]};
    };
    return StTransform{row(outer.s), row(outer.t)};
}

StTransform transform2d(std::array<double, 2> scale, double rotationDegrees, std::array<double, 2> translation) {
    const double radians = rotationDegrees * std::numbers::pi / 180.0;
    const double c = std::cos(radians), s = std::sin(radians);
    return StTransform{{c * scale[0], -s * scale[1], translation[0]}, {s * scale[0], c * scale[1], translation[1]}};
}

std::optional<StTransform> tiledImage(std::array<double, 2> uvtiling, std::array<double, 2> uvoffset,
                                      std::array<double, 2> realworldimagesize,
                                      std::array<double, 2> realworldtilesize) {
    const double ks = realworldtilesize[0] / realworldimagesize[0], kt = realworldtilesize[1] / realworldimagesize[1];
    StTransform out{{uvtiling[0] * ks, 0.0, -uvoffset[0] * ks}, {0.0, uvtiling[1] * kt, -uvoffset[1] * kt}};
    if (!isFinite(out)) return std::nullopt;
    return out;
}

bool isFinite(const StTransform& transform) {
    for (const auto* row : {&transform.s, &transform.t})
        for (double v : *row)
            if (!std::isfinite(v)) return false;
    return true;
}

}  // namespace obscura::harness
