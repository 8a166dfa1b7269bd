#include "pass_support/grading_lattice.h"

#include <algorithm>
#include <utility>

namespace obscura::passes {
namespace {

using Rgb = std::array<float, 3>;

Rgb blend(std::initializer_list<std::pair<float, const Rgb*>> terms) {
    Rgb out{0.0f, 0.0f, 0.0f};
    for (const auto& [weight, value] : terms)
        for (int c = 0; c < 3; ++c) out[c] += weight * (*value)[c];
    return out;
}

}  // namespace

Rgb sampleLattice(const GradingLattice& lattice, Rgb rgb, LatticeInterpolation interpolation) {
    const float last = float(lattice.size - 1);
    uint32_t i0[3], i1[3];
    float f[3];
    for (int c = 0; c < 3; ++c) {
        const float x = std::clamp(rgb[c], 0.0f, 1.0f) * last;
        i0[c] = std::min(uint32_t(x), lattice.size - 2);
        i1[c] = i0[c] + 1;
        f[c] = x - float(i0[c]);
    }
    // Corner (a, b, c): a, b, c in {0, 1} select i0 or i1 along red, green, blue.
    auto corner = [&](int a, int b, int c) -> const Rgb& {
        return lattice.at(a ? i1[0] : i0[0], b ? i1[1] : i0[1], c ? i1[2] : i0[2]);
    };
    const float r = f[0], g = f[1], b = f[2];
    if (interpolation == LatticeInterpolation::Trilinear) {
        Rgb out{0.0f, 0.0f, 0.0f};
        for (int k = 0; k < 8; ++k) {
            const int a = k & 1, bb = (k >> 1) & 1, c = (k >> 2) & 1;
            const float w = (a ? r : 1.0f - r) * (bb ? g : 1.0f - g) * (c ? b : 1.0f - b);
            const Rgb& v = corner(a, bb, c);
            for (int ch = 0; ch < 3; ++ch) out[ch] += w * v[ch];
        }
        return out;
    }
    // The tetrahedron holding the point: the order of its fractions walks from corner 000 to 111
    // along the cube's edges, one axis at a time (largest fraction first).
    const Rgb& c000 = corner(0, 0, 0);
    const Rgb& c111 = corner(1, 1, 1);
    if (r >= g && g >= b) return blend({{1 - r, &c000}, {r - g, &corner(1, 0, 0)}, {g - b, &corner(1, 1, 0)}, {b, &c111}});
    if (r >= b && b >= g) return blend({{1 - r, &c000}, {r - b, &corner(1, 0, 0)}, {b - g, &corner(1, 0, 1)}, {g, &c111}});
    if (b >= r && r >= g) return blend({{1 - b, &c000}, {b - r, &corner(0, 0, 1)}, {r - g, &corner(1, 0, 1)}, {g, &c111}});
    if (g >= r && r >= b) return blend({{1 - g, &c000}, {g - r, &corner(0, 1, 0)}, {r - b, &corner(1, 1, 0)}, {b, &c111}});
    if (g >= b && b >= r) return blend({{1 - g, &c000}, {g - b, &corner(0, 1, 0)}, {b - r, &corner(0, 1, 1)}, {r, &c111}});
    return blend({{1 - b, &c000}, {b - g, &corner(0, 0, 1)}, {g - r, &corner(0, 1, 1)}, {r, &c111}});
}

}  // namespace obscura::passes
