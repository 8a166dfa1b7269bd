#include "harness/image/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace obscura::image {
namespace {

// Where one compared channel lives in each image.
struct ChannelPair {
    int a;
    int b;
};

std::string sizeOf(const Image& img) {
    return std::to_string(img.width) + "x" + std::to_string(img.height);
}

Result<std::vector<ChannelPair>> resolveChannels(const Image& a, const Image& b,
                                                 const CompareOptions& options) {
    if (a.width != b.width || a.height != b.height) {
        return "image sizes differ: " + sizeOf(a) + " vs " + sizeOf(b);
    }
    std::vector<std::string> names = options.channels;
    if (names.empty()) {
        names = {"R", "G", "B"};
        if (a.hasChannel("A") && b.hasChannel("A")) names.push_back("A");
    }
    std::vector<ChannelPair> pairs;
    for (const std::string& name : names) {
        const int ia = a.channelIndex(name);
        const int ib = b.channelIndex(name);
        if (ia < 0) return "channel '" + name + "' missing from the first image";
        if (ib < 0) return "channel '" + name + "' missing from the second image";
        pairs.push_back({ia, ib});
    }
    return pairs;
}

// a - b, except that equal values (including equal infinities, as in a depth background) differ
// by 0 rather than by inf - inf = NaN. NaN is never equal, so NaN anywhere stays a difference.
double difference(float a, float b) {
    return a == b ? 0.0 : static_cast<double>(a) - static_cast<double>(b);
}

// One plane of values per image, clamped to [0,1], for SSIM.
using Plane = std::vector<double>;

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }  // NaN stays NaN

Plane channelPlane(const Image& img, int channel) {
    Plane plane(static_cast<size_t>(img.width) * static_cast<size_t>(img.height));
    for (size_t i = 0; i < plane.size(); ++i) {
        plane[i] = clamp01(img.pixels[i * img.channelCount() + static_cast<size_t>(channel)]);
    }
    return plane;
}

// Rec.709 luminance of channels clamped each to [0,1].
Plane luminancePlane(const Image& img, int r, int g, int b) {
    Plane pr = channelPlane(img, r);
    const Plane pg = channelPlane(img, g);
    const Plane pb = channelPlane(img, b);
    for (size_t i = 0; i < pr.size(); ++i) pr[i] = 0.2126 * pr[i] + 0.7152 * pg[i] + 0.0722 * pb[i];
    return pr;
}

// Normalised Gaussian taps (sigma 1.5) for offsets -radius..radius. At radius 5 this is the
// standard 11-tap window; the 2-D window is the product of two of these.
std::vector<double> gaussianTaps(int radius) {
    std::vector<double> taps;
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        taps.push_back(std::exp(-(i * i) / (2.0 * 1.5 * 1.5)));
        sum += taps.back();
    }
    for (double& t : taps) t /= sum;
    return taps;
}

// Mean SSIM of two planes over all window positions that fit inside the image ("valid"
// filtering, as the reference implementation does).
double ssimPlanes(const Plane& x, const Plane& y, int width, int height) {
    constexpr double kC1 = 0.01 * 0.01;
    constexpr double kC2 = 0.03 * 0.03;
    const int rx = std::min(5, (width - 1) / 2);
    const int ry = std::min(5, (height - 1) / 2);
    const std::vector<double> tx = gaussianTaps(rx);
    const std::vector<double> ty = gaussianTaps(ry);
    const int outW = width - 2 * rx;
    const int outH = height - 2 * ry;

    // Horizontal pass: windowed sums of x, y, x^2, y^2, xy for every row and output column.
    enum { kX, kY, kXX, kYY, kXY, kMoments };
    std::vector<Plane> h(kMoments, Plane(static_cast<size_t>(outW) * static_cast<size_t>(height)));
    for (int row = 0; row < height; ++row) {
        for (int col = 0; col < outW; ++col) {
            double m[kMoments] = {};
            for (int k = 0; k <= 2 * rx; ++k) {
                const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width) +
                                 static_cast<size_t>(col + k);
                m[kX] += tx[k] * x[i];
                m[kY] += tx[k] * y[i];
                m[kXX] += tx[k] * x[i] * x[i];
                m[kYY] += tx[k] * y[i] * y[i];
                m[kXY] += tx[k] * x[i] * y[i];
            }
            const size_t o = static_cast<size_t>(row) * static_cast<size_t>(outW) +
                             static_cast<size_t>(col);
            for (int j = 0; j < kMoments; ++j) h[j][o] = m[j];
        }
    }

    // Vertical pass, then SSIM of each window.
    double total = 0.0;
    for (int row = 0; row < outH; ++row) {
        for (int col = 0; col < outW; ++col) {
            double m[kMoments] = {};
            for (int k = 0; k <= 2 * ry; ++k) {
                const size_t i = static_cast<size_t>(row + k) * static_cast<size_t>(outW) +
                                 static_cast<size_t>(col);
                for (int j = 0; j < kMoments; ++j) m[j] += ty[k] * h[j][i];
            }
            const double muX = m[kX];
            const double muY = m[kY];
            const double varX = m[kXX] - muX * muX;
            const double varY = m[kYY] - muY * muY;
            const double covXY = m[kXY] - muX * muY;
            total += ((2.0 * muX * muY + kC1) * (2.0 * covXY + kC2)) /
                     ((muX * muX + muY * muY + kC1) * (varX + varY + kC2));
        }
    }
    return total / (static_cast<double>(outW) * static_cast<double>(outH));
}

double ssim(const Image& a, const Image& b, const std::vector<ChannelPair>& pairs) {
    // Luminance when the colour channels are among those compared.
    const int r = a.channelIndex("R");
    const int g = a.channelIndex("G");
    const int bl = a.channelIndex("B");
    auto compared = [&](int channel) {
        return std::any_of(pairs.begin(), pairs.end(),
                           [&](const ChannelPair& p) { return p.a == channel; });
    };
    if (r >= 0 && g >= 0 && bl >= 0 && compared(r) && compared(g) && compared(bl)) {
        return ssimPlanes(luminancePlane(a, r, g, bl),
                          luminancePlane(b, b.channelIndex("R"), b.channelIndex("G"),
                                         b.channelIndex("B")),
                          a.width, a.height);
    }
    double sum = 0.0;
    for (const ChannelPair& p : pairs) {
        sum += ssimPlanes(channelPlane(a, p.a), channelPlane(b, p.b), a.width, a.height);
    }
    return sum / static_cast<double>(pairs.size());
}

}  // namespace

Result<CompareMetrics> compare(const Image& a, const Image& b, const CompareOptions& options) {
    const Result<std::vector<ChannelPair>> resolved = resolveChannels(a, b, options);
    if (isError(resolved)) return errorOf(resolved);
    const std::vector<ChannelPair>& pairs = std::get<std::vector<ChannelPair>>(resolved);

    const size_t pixelCount = static_cast<size_t>(a.width) * static_cast<size_t>(a.height);
    if (pixelCount == 0) return std::string("images are empty");

    CompareMetrics metrics;
    metrics.width = a.width;
    metrics.height = a.height;

    double sumAbs = 0.0;
    double sumSquared = 0.0;
    bool sawNaN = false;
    for (size_t i = 0; i < pixelCount; ++i) {
        for (const ChannelPair& p : pairs) {
            const double d = std::abs(difference(a.pixels[i * a.channelCount() + p.a],
                                                 b.pixels[i * b.channelCount() + p.b]));
            sumAbs += d;
            sumSquared += d * d;
            sawNaN = sawNaN || std::isnan(d);
            metrics.maxAbsError = std::max(metrics.maxAbsError, d);
        }
    }
    // std::max drops NaN; put it back so a NaN pixel cannot hide.
    if (sawNaN) metrics.maxAbsError = std::numeric_limits<double>::quiet_NaN();

    const double count = static_cast<double>(pixelCount * pairs.size());
    const double mse = sumSquared / count;
    metrics.meanAbsError = sumAbs / count;
    metrics.rmse = std::sqrt(mse);
    metrics.psnr =
        mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
    metrics.ssim = ssim(a, b, pairs);
    return metrics;
}

Result<Image> makeDiffImage(const Image& a, const Image& b, const CompareOptions& options) {
    const Result<std::vector<ChannelPair>> resolved = resolveChannels(a, b, options);
    if (isError(resolved)) return errorOf(resolved);
    const std::vector<ChannelPair>& pairs = std::get<std::vector<ChannelPair>>(resolved);

    Image diff = Image::make(a.width, a.height, {"R", "G", "B"});
    const size_t pixelCount = static_cast<size_t>(a.width) * static_cast<size_t>(a.height);
    // Channels beyond the first three (or all of them, with fewer than three) show in every
    // output channel.
    const size_t firstShared = pairs.size() >= 3 ? 3 : 0;
    std::vector<float> scaled(pairs.size());
    for (size_t i = 0; i < pixelCount; ++i) {
        for (size_t k = 0; k < pairs.size(); ++k) {
            const double d = std::abs(difference(a.pixels[i * a.channelCount() + pairs[k].a],
                                                 b.pixels[i * b.channelCount() + pairs[k].b]));
            scaled[k] = std::isnan(d) ? 1.0f : static_cast<float>(std::min(d * 10.0, 1.0));
        }
        float shared = 0.0f;
        for (size_t k = firstShared; k < pairs.size(); ++k) shared = std::max(shared, scaled[k]);
        for (size_t c = 0; c < 3; ++c) {
            diff.pixels[i * 3 + c] = firstShared == 3 ? std::max(scaled[c], shared) : shared;
        }
    }
    return diff;
}

}  // namespace obscura::image
