// Best-fit normals (Kaplanyan 2010, seed 004 appendix A): the search that builds the fitting-scale
// table. It runs at build time (generate_best_fit_table.cpp writes the table the library embeds):
// the search over a million texels took most of a process's start-up on a 2-core machine.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace obscura::passes {

// The table is kTableSize^2 texels: u = larger minor component |n|, v = smaller / larger.
constexpr uint32_t kBestFitTableSize = 1024;

// Appendix A, FindMinimumQuantizationError: the scale t in (0, 1] of the max-normalised
// direction whose 8-bit quantisation has the smallest error.
float findBestFitScale(const std::array<float, 3>& direction);

// The unit direction texel (i, j) of the table stands for: z the major axis, x the larger minor
// component.
std::array<float, 3> bestFitTexelDirection(uint32_t i, uint32_t j);

// Texel (i, j)'s entry: the scale as R16_UNORM.
uint16_t bestFitTableEntry(uint32_t i, uint32_t j);

// The whole table, row by row (j outer), computed on every core.
std::vector<uint16_t> computeBestFitScaleTable();

}  // namespace obscura::passes
