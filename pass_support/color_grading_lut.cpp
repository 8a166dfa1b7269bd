#include "pass_support/color_grading_lut.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace obscura::passes {

uint16_t floatToHalf(float value) {
    uint32_t f = std::bit_cast<uint32_t>(value);
    uint32_t sign = (f >> 16) & 0x8000u;
    int32_t exponent = int32_t((f >> 23) & 0xffu) - 127 + 15;
    uint32_t mantissa = f & 0x7fffffu;
    if (((f >> 23) & 0xffu) == 0xffu) return uint16_t(sign | 0x7c00u | (mantissa ? 0x200u : 0u));  // inf, nan
    if (exponent >= 31) return uint16_t(sign | 0x7c00u);                                           // overflow
    if (exponent <= 0) {
        if (exponent < -10) return uint16_t(sign);  // underflow to zero
        mantissa |= 0x800000u;                       // subnormal half
        uint32_t shift = uint32_t(14 - exponent);
        uint32_t half = mantissa >> shift;
        uint32_t rest = mantissa & ((1u << shift) - 1u), halfway = 1u << (shift - 1u);
        if (rest > halfway || (rest == halfway && (half & 1u))) ++half;
        return uint16_t(sign | half);
    }
    uint32_t half = sign | (uint32_t(exponent) << 10) | (mantissa >> 13);
    uint32_t rest = mantissa & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ++half;  // may carry into the exponent: correct
    return uint16_t(half);
}

std::string ColorGradingLut::update(gpu::FrameBackend& backend, const ColorLutRequest& request,
                                    const DisplayGrade& grade) {
    std::string key = request.configPath + '\n' + request.display + '\n' + request.view + '\n' + request.look;
    if (grade.lattice) key += '\n' + grade.key + '\n' + std::to_string(int(grade.interpolation));
    if (key_ && *key_ == key && texture_) return {};
    auto baked = bakeColorLut(request);
    if (auto* error = std::get_if<std::string>(&baked)) return *error;
    lut_ = std::move(std::get<ColorLut>(baked));
    // The grade takes the display values the view gives, so it sees them clamped as a screen does.
    if (grade.lattice)
        for (size_t i = 0; i < lut_.rgba.size(); i += 4) {
            auto graded = sampleLattice(*grade.lattice, {lut_.rgba[i], lut_.rgba[i + 1], lut_.rgba[i + 2]},
                                        grade.interpolation);
            std::copy(graded.begin(), graded.end(), lut_.rgba.begin() + ptrdiff_t(i));
        }
    std::vector<uint16_t> texels(lut_.rgba.size());
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = floatToHalf(lut_.rgba[i]);
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.width = desc.height = desc.depth = lut_.size;
    texture_ = backend.createTexture(desc, texels.data(), texels.size() * sizeof(uint16_t), "color grading LUT");
    key_ = key;
    return {};
}

}  // namespace obscura::passes
