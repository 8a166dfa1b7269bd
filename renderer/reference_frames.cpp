#include "renderer/reference_frames.h"

#include <cmath>
#include <numeric>

namespace obscura::renderer {
namespace {

// Van der Corput: the digits of `index` in `base`, mirrored about the radix point.
double radicalInverse(uint32_t index, uint32_t base) {
    double inverse = 0.0, digitWeight = 1.0 / base;
    for (; index > 0; index /= base, digitWeight /= base) inverse += digitWeight * (index % base);
    return inverse;
}

// The multiplier of a rank-1 lattice k -> (k g mod N) / N: the integer nearest N `ratio` that
// shares no factor with N, so that the lattice is a permutation (every 1/N of the interval gets
// one point) and, for an irrational ratio, far from aligned with k / N (Korobov's golden-ratio
// choice, (sqrt 5 - 1) / 2).
constexpr double kGoldenRatio = 0.6180339887498949;
constexpr double kPlasticRatio = 0.7548776662466927;  // 1 / rho, rho^3 = rho + 1

uint32_t latticeMultiplier(uint32_t count, double ratio) {
    uint32_t ideal = static_cast<uint32_t>(std::lround(count * ratio));
    for (uint32_t step = 0;; ++step) {
        for (uint32_t g : {ideal + step, ideal - step})
            if (g > 0 && g < count && std::gcd(g, count) == 1) return g;
        if (step > count) return 1;
    }
}

// Point k of the Hammersley set of `count` on [-1, 1]^2, both coordinates centred in their strata
// (the radical inverse steps by 1 / N for N = 2^m).
std::array<double, 2> hammersleyPoint(uint32_t k, uint32_t count) {
    return {2.0 * (k + 0.5) / count - 1.0, 2.0 * (radicalInverse(k, 2) + 0.5 / count) - 1.0};
}

}  // namespace

std::array<double, 2> pixelBoxJitter(uint32_t index, uint32_t count, uint32_t samples) {
    if (count == 0 || samples == 0) return {0.0, 0.0};
    index %= count;
    // Both coordinates centred in their strata: the points' mean is the strip's centre, and no
    // sample lands on a box's edge, where rounding would give it to either pixel.
    return {(radicalInverse(index, 2) + 0.5 / count - 0.5) / samples, (index + 0.5) / count - 0.5};
}

uint32_t shutterStratum(uint32_t index, uint32_t count) {
    return count > 0 ? uint32_t(uint64_t(index) * latticeMultiplier(count, kGoldenRatio) % count) : 0;
}

uint32_t referenceSamples(const PixelFilter& filter) {
    return isPixelBox(filter) ? 4u : 1u;
}

std::vector<ReferenceSubFrame> referenceSubFrames(uint32_t count, const passes::ApertureShape& aperture,
                                                  const PixelFilter& filter, uint32_t samples) {
    PixelFilterWarp warp(filter);
    std::vector<ReferenceSubFrame> frames;
    frames.reserve(count);
    for (uint32_t k = 0; k < count; ++k) {
        std::array<double, 2> lens = passes::sampleAperture(hammersleyPoint(k, count), aperture);
        double shutter = (double(shutterStratum(k, count)) + 0.5) / count;
        std::array<double, 2> emitter{radicalInverse(k, 7), radicalInverse(k, 11)};
        std::array<double, 2> jitter{warp.offset(radicalInverse(k, 3) - 0.5), warp.offset(radicalInverse(k, 5) - 0.5)};
        if (samples > 1) jitter[0] = (radicalInverse(k, 3) - 0.5) / samples;
        frames.push_back({lens, shutter, jitter, emitter});
    }
    return frames;
}

uint32_t stillLensCells(uint32_t count) { return count % 2 == 0 ? count / 2 : count; }

StillLensSample stillLensSample(uint32_t index, uint32_t count, const passes::ApertureShape& aperture) {
    if (count == 0) return {{0.0, 0.0}, {}};
    // Frames 2c and 2c + 1 share cell c (stillLensCells).
    const uint32_t visits = count / stillLensCells(count);
    index = (index % count) / visits;
    count /= visits;
    uint32_t rows = 1;
    for (uint32_t r = 1; r * r <= count; ++r)
        if (count % r == 0) rows = r;
    const uint32_t columns = count / rows;
    uint32_t cell = uint32_t(uint64_t(index % count) * latticeMultiplier(count, kPlasticRatio) % count);
    passes::ApertureCell c;
    c.halfSize = {1.0 / columns, 1.0 / rows};
    c.centre = {(2.0 * (cell % columns) + 1.0) / columns - 1.0, (2.0 * (cell / columns) + 1.0) / rows - 1.0};
    return {passes::sampleAperture(c.centre, aperture), c};
}

}  // namespace obscura::renderer
