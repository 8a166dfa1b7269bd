#include "delegate/reference_frames.h"

namespace obscura::delegate {
namespace {

// Van der Corput: the digits of `index` in `base`, mirrored about the radix point.
double radicalInverse(uint32_t index, uint32_t base) {
    double inverse = 0.0, digitWeight = 1.0 / base;
    for (; index > 0; index /= base, digitWeight /= base) inverse += digitWeight * (index % base);
    return inverse;
}

}  // namespace

std::vector<ReferenceSubFrame> referenceSubFrames(uint32_t count, const passes::ApertureShape& aperture) {
    std::vector<ReferenceSubFrame> frames;
    frames.reserve(count);
    for (uint32_t k = 0; k < count; ++k) {
        // Both coordinates centred in their strata (the radical inverse steps by 1 / N for N = 2^m).
        std::array<double, 2> square{2.0 * (k + 0.5) / count - 1.0, 2.0 * (radicalInverse(k, 2) + 0.5 / count) - 1.0};
        passes::ApertureSample lens = passes::sampleAperture(square, aperture);
        frames.push_back({lens.position, lens.area, radicalInverse(k, 3),
                          {radicalInverse(k, 5) - 0.5, radicalInverse(k, 7) - 0.5}});
    }
    return frames;
}

}  // namespace obscura::delegate
