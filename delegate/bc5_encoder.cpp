#include "delegate/bc5_encoder.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::delegate {
namespace {

constexpr size_t kTexels = 16;
// Blocks whose common encoding errs by less than this everywhere are kept as they are (the talk's
// adaptive approach): below a tenth of a degree the search gains nothing visible.
constexpr float kSearchThresholdDegrees = 0.1f;

// A BC4 block's eight values with endpoint0 > endpoint1 (the mode of six interpolated values;
// the other mode, with 0 and 1 as fixed entries, is never written).
struct Bc4 {
    int e0 = 255, e1 = 0;
    std::array<float, 8> palette() const {
        std::array<float, 8> p{};
        p[0] = float(e0) / 255.0f;
        p[1] = float(e1) / 255.0f;
        for (int i = 2; i < 8; ++i) p[size_t(i)] = (float(8 - i) * float(e0) + float(i - 1) * float(e1)) / (7.0f * 255.0f);
        return p;
    }
};

// Endpoints a > b from the extremes of `values` (in [0, 1]); equal extremes are pulled apart by
// one code so that the six-value mode applies.
Bc4 extremes(const std::array<float, kTexels>& values) {
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    Bc4 b{int(std::lround(*hi * 255.0f)), int(std::lround(*lo * 255.0f))};
    if (b.e0 == b.e1) (b.e0 < 255 ? b.e0 : b.e1) += b.e0 < 255 ? 1 : -1;
    return b;
}

// The palette entries just below and just above v (the nearest is one of them).
std::array<uint8_t, 2> bracket(const std::array<float, 8>& palette, float v) {
    int below = -1, above = -1;
    for (int i = 0; i < 8; ++i) {
        const float p = palette[size_t(i)];
        if (p <= v && (below < 0 || p > palette[size_t(below)])) below = i;
        if (p >= v && (above < 0 || p < palette[size_t(above)])) above = i;
    }
    if (below < 0) below = above;
    if (above < 0) above = below;
    return {uint8_t(below), uint8_t(above)};
}

uint8_t nearest(const std::array<float, 8>& palette, float v) {
    const auto [below, above] = bracket(palette, v);
    return std::abs(palette[below] - v) <= std::abs(palette[above] - v) ? below : above;
}

float cosineBetween(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    return std::clamp(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], -1.0f, 1.0f);
}

float angleBetween(const std::array<float, 3>& a, const std::array<float, 3>& b) { return std::acos(cosineBetween(a, b)); }

struct Block {
    std::array<std::array<float, 3>, kTexels> reference;
    std::array<float, kTexels> x, y;  // the targets, 0.5 n + 0.5
};

struct Encoded {
    Bc4 x, y;
    std::array<uint8_t, kTexels> ix{}, iy{};
    float totalAngle = 0.0f, maxAngle = 0.0f;
};

Encoded perChannel(const Block& block) {
    Encoded e{extremes(block.x), extremes(block.y)};
    const auto px = e.x.palette(), py = e.y.palette();
    for (size_t t = 0; t < kTexels; ++t) {
        e.ix[t] = nearest(px, block.x[t]);
        e.iy[t] = nearest(py, block.y[t]);
        const float a = angleBetween(reconstructNormal(px[e.ix[t]], py[e.iy[t]]), block.reference[t]);
        e.totalAngle += a;
        e.maxAngle = std::max(e.maxAngle, a);
    }
    return e;
}

// Given endpoints, each texel's index pair minimising its angle among the values bracketing its
// targets (which include the nearest of each channel, the common encoder's pair). The angle falls
// as the cosine rises, so the pairs are compared by their cosines and only the chosen one's angle
// is taken (the search evaluates this for every endpoint move: one arc cosine a texel, not four).
Encoded jointIndices(const Block& block, Bc4 x, Bc4 y) {
    Encoded e{x, y};
    const auto px = x.palette(), py = y.palette();
    for (size_t t = 0; t < kTexels; ++t) {
        const auto bx = bracket(px, block.x[t]), by = bracket(py, block.y[t]);
        float bestCosine = -2.0f;
        for (uint8_t i : bx)
            for (uint8_t j : by) {
                const float c = cosineBetween(reconstructNormal(px[i], py[j]), block.reference[t]);
                if (c > bestCosine) bestCosine = c, e.ix[t] = i, e.iy[t] = j;
            }
        const float best = std::acos(bestCosine);
        e.totalAngle += best;
        e.maxAngle = std::max(e.maxAngle, best);
    }
    return e;
}

bool valid(const Bc4& b) { return b.e0 > b.e1 && b.e0 <= 255 && b.e1 >= 0; }

// Coordinate descent over the four endpoints, coarse steps first, keeping any move that lowers
// the block's summed angle without raising its largest above the common encoding's (so neither
// the mean nor the maximum angle of an image rises above the common encoder's).
Encoded normalAware(const Block& block) {
    const Encoded common = perChannel(block);
    if (common.maxAngle * 180.0f / std::numbers::pi_v<float> < kSearchThresholdDegrees) return common;
    // Each texel's pair is at least as good as the common encoder's, which is among those tried.
    Encoded best = jointIndices(block, common.x, common.y);
    for (int step : {8, 4, 2, 1}) {
        for (bool improved = true; improved;) {
            improved = false;
            for (int endpoint = 0; endpoint < 4; ++endpoint)
                for (int sign : {-1, 1}) {
                    Bc4 x = best.x, y = best.y;
                    int* e = endpoint == 0 ? &x.e0 : endpoint == 1 ? &x.e1 : endpoint == 2 ? &y.e0 : &y.e1;
                    *e += sign * step;
                    if (!valid(x) || !valid(y)) continue;
                    Encoded candidate = jointIndices(block, x, y);
                    if (candidate.totalAngle < best.totalAngle && candidate.maxAngle <= common.maxAngle)
                        best = candidate, improved = true;
                }
        }
    }
    return best;
}

// BC4 layout: endpoint0, endpoint1, then 48 bits of 3-bit indices, texel 0 in the lowest bits.
void writeBc4(std::byte* out, const Bc4& b, const std::array<uint8_t, kTexels>& indices) {
    out[0] = std::byte(uint8_t(b.e0));
    out[1] = std::byte(uint8_t(b.e1));
    uint64_t bits = 0;
    for (size_t t = 0; t < kTexels; ++t) bits |= uint64_t(indices[t]) << (3 * t);
    for (size_t i = 0; i < 6; ++i) out[2 + i] = std::byte(uint8_t(bits >> (8 * i)));
}

std::array<float, kTexels> readBc4(const std::byte* in) {
    const Bc4 b{std::to_integer<int>(in[0]), std::to_integer<int>(in[1])};
    uint64_t bits = 0;
    for (size_t i = 0; i < 6; ++i) bits |= uint64_t(std::to_integer<uint8_t>(in[2 + i])) << (8 * i);
    std::array<float, 8> p{};
    if (b.e0 > b.e1) {
        p = b.palette();
    } else {  // five interpolated values, then 0 and 1
        p[0] = float(b.e0) / 255.0f;
        p[1] = float(b.e1) / 255.0f;
        for (int i = 2; i < 6; ++i) p[size_t(i)] = (float(6 - i) * float(b.e0) + float(i - 1) * float(b.e1)) / (5.0f * 255.0f);
        p[6] = 0.0f;
        p[7] = 1.0f;
    }
    std::array<float, kTexels> values{};
    for (size_t t = 0; t < kTexels; ++t) values[t] = p[(bits >> (3 * t)) & 7];
    return values;
}

}  // namespace

std::array<float, 3> reconstructNormal(float x, float y) {
    const float nx = 2.0f * x - 1.0f, ny = 2.0f * y - 1.0f;
    const float z = std::sqrt(std::max(0.0f, 1.0f - nx * nx - ny * ny));
    const float length = std::sqrt(nx * nx + ny * ny + z * z);
    return {nx / length, ny / length, z / length};
}

std::vector<std::byte> encodeBc5(const NormalImage& image, Bc5Encoder encoder) {
    const uint32_t blocksX = (image.width + 3) / 4, blocksY = (image.height + 3) / 4;
    std::vector<std::byte> out(size_t(blocksX) * blocksY * 16);
    tbb::parallel_for(uint32_t(0), blocksY, [&](uint32_t by) {
        for (uint32_t bx = 0; bx < blocksX; ++bx) {
            Block block;
            for (size_t t = 0; t < kTexels; ++t) {
                const uint32_t x = std::min(bx * 4 + uint32_t(t % 4), image.width - 1);
                const uint32_t y = std::min(by * 4 + uint32_t(t / 4), image.height - 1);
                block.reference[t] = image.normals[size_t(y) * image.width + x];
                block.x[t] = 0.5f * block.reference[t][0] + 0.5f;
                block.y[t] = 0.5f * block.reference[t][1] + 0.5f;
            }
            const Encoded e = encoder == Bc5Encoder::PerChannel ? perChannel(block) : normalAware(block);
            std::byte* dst = &out[(size_t(by) * blocksX + bx) * 16];
            writeBc4(dst, e.x, e.ix);
            writeBc4(dst + 8, e.y, e.iy);
        }
    });
    return out;
}

NormalImage decodeBc5(const std::vector<std::byte>& blocks, uint32_t width, uint32_t height) {
    NormalImage image{width, height, std::vector<std::array<float, 3>>(size_t(width) * height)};
    const uint32_t blocksX = (width + 3) / 4;
    for (uint32_t by = 0; by < (height + 3) / 4; ++by)
        for (uint32_t bx = 0; bx < blocksX; ++bx) {
            const std::byte* src = &blocks[(size_t(by) * blocksX + bx) * 16];
            const auto xs = readBc4(src), ys = readBc4(src + 8);
            for (size_t t = 0; t < kTexels; ++t) {
                const uint32_t x = bx * 4 + uint32_t(t % 4), y = by * 4 + uint32_t(t / 4);
                if (x < width && y < height) image.normals[size_t(y) * width + x] = reconstructNormal(xs[t], ys[t]);
            }
        }
    return image;
}

AngularError angularError(const NormalImage& reference, const NormalImage& decoded) {
    AngularError e;
    double sum = 0.0;
    for (size_t i = 0; i < reference.normals.size(); ++i) {
        const double a = angleBetween(reference.normals[i], decoded.normals[i]) * 180.0 / std::numbers::pi;
        sum += a;
        e.maxDegrees = std::max(e.maxDegrees, a);
    }
    e.meanDegrees = reference.normals.empty() ? 0.0 : sum / double(reference.normals.size());
    return e;
}

}  // namespace obscura::delegate
