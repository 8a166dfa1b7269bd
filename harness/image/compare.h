// Image comparison for the harness: error metrics between a rendered image and a reference,
// and a difference image for people to look at.
//
// All metrics are computed on the values as given, whatever they mean: for linear HDR data
// PSNR still uses a peak of 1.0, so it measures error relative to diffuse white, not to the
// brightest pixel, and can be negative where errors exceed 1. NaN or infinite values make the
// metrics NaN (a comparison that must fail), never silently pass.
#pragma once

#include <string>
#include <vector>

#include "harness/image/image.h"

namespace obscura::image {

struct CompareOptions {
    // Channels to compare, by name. Empty: R, G, B, plus A when both images have it.
    std::vector<std::string> channels;
};

struct CompareMetrics {
    // Over all compared channels of all pixels:
    double psnr = 0.0;          // dB, 10 * log10(1 / mse) (peak 1.0); +inf for identical images
    double maxAbsError = 0.0;
    double meanAbsError = 0.0;
    double rmse = 0.0;
    // Mean SSIM (Wang et al. 2004: 11x11 Gaussian window, sigma 1.5, C1 = 0.01^2, C2 = 0.03^2,
    // dynamic range 1) over the windows that fit inside the image; on images smaller than 11
    // pixels the window is cut to fit. Values are clamped to [0,1] first, for HDR inputs.
    // When R, G and B are compared, SSIM is of Rec.709 luminance
    // Y = 0.2126 R + 0.7152 G + 0.0722 B; otherwise the mean of each compared channel's SSIM.
    double ssim = 0.0;
    int width = 0;
    int height = 0;
};

// Errors (as a message) when the sizes differ or a channel is missing from either image.
Result<CompareMetrics> compare(const Image& a, const Image& b, const CompareOptions& options = {});

// An RGB image of |a - b| * 10, clamped to [0,1], ready for writePng. With three or more compared
// channels, the first three give R, G, B and the rest (e.g. A) add to all three (per-pixel max),
// so an alpha-only difference shows grey; with fewer, the largest difference shows as grey.
// NaN differences show as 1. Fails like compare().
Result<Image> makeDiffImage(const Image& a, const Image& b, const CompareOptions& options = {});

}  // namespace obscura::image
