// A grade held as a lattice of display values (seed 004 "Color grading": the LUT an artist made
// by grading the chart; Selan 2007). Display RGB in [0,1] goes in, graded display RGB comes out,
// interpolated between the lattice points either way the setting `grading:interpolation` names.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace obscura::passes {

enum class LatticeInterpolation {
    // Seed 004's: the hardware's trilinear filter of the 3D texture.
    Trilinear,
    // Kasson et al. 1995 / Kang 1997: the cube split into six tetrahedra along its grey diagonal,
    // four points blended per lookup. Greys interpolate from grey lattice points only, so a grade
    // that keeps greys neutral keeps them neutral between the lattice points too.
    Tetrahedral,
};

struct GradingLattice {
    uint32_t size = 0;                          // points per axis
    std::vector<std::array<float, 3>> values;   // size^3, r fastest, then g, then b
    const std::array<float, 3>& at(uint32_t r, uint32_t g, uint32_t b) const {
        return values[(std::size_t(b) * size + g) * size + r];
    }
};

// The graded value of `rgb` (clamped to [0,1] first).
std::array<float, 3> sampleLattice(const GradingLattice& lattice, std::array<float, 3> rgb,
                                   LatticeInterpolation interpolation);

}  // namespace obscura::passes
