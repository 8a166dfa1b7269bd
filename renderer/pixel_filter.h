// The pixel filter of a still (render settings pixelFilter, pixelFilter:width), as offline
// renderers have it: a still's accumulated frames and the reference's sub-frames take their sub-pixel
// offsets distributed as the filter (importance sampling, as Cycles draws its film samples from a
// filter table), so that their equally weighted mean is the filtered image. Box of width 1 is the
// pixel's own square, the integral the ground truth is measured by.
#pragma once

#include <array>
#include <string_view>

namespace obscura::renderer {

enum class PixelFilterKind { Box, Gaussian, BlackmanHarris };

struct PixelFilter {
    PixelFilterKind kind = PixelFilterKind::Box;
    double width = 1.0;  // the filter's support, pixels (Cycles' filter_width)
};

// Whether `filter` is the pixel's own square (the box of width 1): MSAA samples then resolve over
// the pixel's box (passes::SampleResolve::PixelBox), in a still's frames and the reference's.
inline bool isPixelBox(const PixelFilter& filter) { return filter.kind == PixelFilterKind::Box && filter.width == 1.0; }

// The render setting's token ("box", "gaussian", "blackman-harris"); box for anything else.
PixelFilterKind pixelFilterKind(std::string_view token);

// The separable 1D filter's offsets: offset(u) for u uniform in [-0.5, 0.5) is distributed as the
// filter over [-width / 2, width / 2] (the inverse of its cumulative distribution, tabulated);
// offset(0) is 0 (every filter is symmetric), so the first frame of a still still looks through
// the pixel's centre.
class PixelFilterWarp {
public:
    explicit PixelFilterWarp(const PixelFilter& filter);
    double offset(double u) const;

private:
    static constexpr int kBins = 256;
    PixelFilter filter_;
    std::array<double, kBins + 1> cumulative_{};  // normalised: 0 at -width / 2, 1 at width / 2
};

}  // namespace obscura::renderer
