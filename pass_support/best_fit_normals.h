// Best-fit normals (Kaplanyan 2010, seed 004 appendix A). The fitting-scale table is built once
// per process from the appendix's search and uploaded as a 2D texture for the G-buffer pass;
// the CPU encoder mirrors shaders/common/best_fit_normals.glsl for tests.
#pragma once

#include "gpu/frame_backend.h"

#include <array>
#include <cstdint>
#include <vector>

namespace obscura::passes {

// The table is kTableSize^2 texels: u = larger minor component |n|, v = smaller / larger.
constexpr uint32_t kBestFitTableSize = 1024;

// Appendix A, FindMinimumQuantizationError: the scale t in (0, 1] of the max-normalised
// direction whose 8-bit quantisation has the smallest error.
float findBestFitScale(const std::array<float, 3>& direction);

// The whole table, R16_UNORM values of the scale (built in parallel; cached for the process).
const std::vector<uint16_t>& bestFitScaleTable();

// CPU twin of encodeBestFitNormal(): 8-bit RGB of a unit normal.
std::array<uint8_t, 3> encodeBestFitNormal(const std::array<float, 3>& normal);
// Plain storage for comparison: n * 0.5 + 0.5 quantised to 8 bits.
std::array<uint8_t, 3> encodeNormalizedNormal(const std::array<float, 3>& normal);
std::array<float, 3> decodeNormal(const std::array<uint8_t, 3>& stored);

gpu::ImagePtr createBestFitNormalsTexture(gpu::FrameBackend& backend);

}  // namespace obscura::passes
