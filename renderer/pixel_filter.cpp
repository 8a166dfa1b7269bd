#include "renderer/pixel_filter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::renderer {
namespace {

// Cycles' filter functions (intern/cycles/scene/film.cpp), v in [-width / 2, width / 2]: a
// Gaussian of standard deviation width / 12, and the 4-term Blackman-Harris window over the width.
double filterValue(const PixelFilter& f, double v) {
    switch (f.kind) {
    case PixelFilterKind::Gaussian: {
        double x = v * 6.0 / f.width;
        return std::exp(-2.0 * x * x);
    }
    case PixelFilterKind::BlackmanHarris: {
        double x = 2.0 * std::numbers::pi * (v / f.width + 0.5);
        return 0.35875 - 0.48829 * std::cos(x) + 0.14128 * std::cos(2.0 * x) - 0.01168 * std::cos(3.0 * x);
    }
    case PixelFilterKind::Box: break;
    }
    return 1.0;
}

}  // namespace

PixelFilterKind pixelFilterKind(std::string_view token) {
    if (token == "gaussian") return PixelFilterKind::Gaussian;
    if (token == "blackman-harris") return PixelFilterKind::BlackmanHarris;
    return PixelFilterKind::Box;
}

PixelFilterWarp::PixelFilterWarp(const PixelFilter& filter) : filter_(filter) {
    if (filter_.kind == PixelFilterKind::Box) return;
    // The midpoint rule per bin; the filter is symmetric, so the table is too.
    for (int i = 0; i < kBins; ++i) {
        double v = ((i + 0.5) / kBins - 0.5) * filter_.width;
        cumulative_[size_t(i) + 1] = cumulative_[size_t(i)] + std::max(filterValue(filter_, v), 0.0);
    }
    for (double& c : cumulative_) c /= cumulative_.back();
}

double PixelFilterWarp::offset(double u) const {
    if (filter_.kind == PixelFilterKind::Box) return u * filter_.width;
    double p = std::clamp(u + 0.5, 0.0, 1.0);
    if (p == 0.5) return 0.0;
    auto upper = std::upper_bound(cumulative_.begin(), cumulative_.end(), p);
    size_t bin = size_t(std::clamp<std::ptrdiff_t>(upper - cumulative_.begin() - 1, 0, kBins - 1));
    double lo = cumulative_[bin], hi = cumulative_[bin + 1];
    double within = hi > lo ? (p - lo) / (hi - lo) : 0.5;
    return ((double(bin) + within) / kBins - 0.5) * filter_.width;
}

}  // namespace obscura::renderer
