// Best-fit normals (Kaplanyan 2010, seed 004 appendix A). The fitting-scale table (the appendix's
// search, run at build time: best_fit_search.h) is uploaded as a 2D texture for the G-buffer pass;
// the CPU encoder mirrors shaders/common/best_fit_normals.glsl for tests.
#pragma once

#include "gpu/frame_backend.h"
#include "pass_support/best_fit_search.h"

#include <array>
#include <cstdint>
#include <span>

namespace obscura::passes {

// The whole table as the build wrote it, R16_UNORM values of the scale.
std::span<const uint16_t> bestFitScaleTable();

// CPU twin of encodeBestFitNormal(): 8-bit RGB of a unit normal.
std::array<uint8_t, 3> encodeBestFitNormal(const std::array<float, 3>& normal);
// Plain storage for comparison: n * 0.5 + 0.5 quantised to 8 bits.
std::array<uint8_t, 3> encodeNormalizedNormal(const std::array<float, 3>& normal);
std::array<float, 3> decodeNormal(const std::array<uint8_t, 3>& stored);

gpu::ImagePtr createBestFitNormalsTexture(gpu::FrameBackend& backend);

}  // namespace obscura::passes
