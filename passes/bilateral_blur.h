// The bilateral blur of SSAO's accumulated obscurance (seed 004 "SSAO improvements"): both axes of
// the separable depth-aware blur in one pass (shaders/bilateral_blur.comp). Chained by return value
// as Filament chains its effects: `ambient.accessibility = addBilateralBlurPass(graph, ambient)`.
#pragma once

#include "passes/frame_resources.h"

namespace obscura::passes {

// Blurs `ssao.accessibility` (its first channel) guided by `ssao.halfDepth`; returns the blurred
// accessibility, kSsaoAccessibilityFormat, the size of the input.
gpu::ImageHandle addBilateralBlurPass(gpu::FrameGraph& graph, const SsaoResult& ssao);

}  // namespace obscura::passes
