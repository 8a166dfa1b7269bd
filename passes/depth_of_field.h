// Depth of field (frame step 10; seed 000 "Depth of field"): a physically based circle of
// confusion from the camera's lens, and the separable flexible filter at half resolution.
//   dof_downsample        CoC per pixel (one multiply-add), bilateral downscale to half resolution
//                         of the near and far fields, each premultiplied by its CoC (R11G11B10F),
//                         and the half-resolution CoC (R8G8: near, far);
//   dof_tile_min_max      the CoC per tile: the near field's max and the far field's max (the min
//                         of the signed CoC, whose far field is negative);
//   dof_tile_neighbourhood the near max over the tiles a near CoC can reach from (scatter as gather);
//   dof_gather            first pass, N^2 taps (7x7) for both fields, branching on the tiles;
//   dof_flood_fill        second pass, 3x3 taps combined by boolean union (max) that fill the
//                         shape between the first pass's taps (McIntosh et al. 2012);
//   dof_composite         far field upscaled bilaterally, near field freely, both with bicubic
//                         weights (Sigg & Hadwiger 2005), blended non-linearly over the sharp image.
#pragma once

#include "passes/frame_resources.h"
#include "pass_support/thin_lens.h"

namespace obscura::passes {

// Taps per side of the first gather pass: 7 (49 taps) as the seed; more is a quality setting.
constexpr int kDefaultDofTapsPerSide = 7;
constexpr int kMinDofTapsPerSide = 3;
constexpr int kMaxDofTapsPerSide = 15;

struct DepthOfFieldSettings {
    CocFromDepth coc;        // signed CoC radius in pixels from device depth
    ApertureShape aperture;
    int tapsPerSide = kDefaultDofTapsPerSide;
};

// The largest CoC radius the filter reaches, in full-resolution pixels ("limit offset range to
// minimize undersampling"): the two passes place N^2 x 9 points over the aperture; at a radius of
// 2N half-resolution texels they lie about one texel apart, which bilinear fetches still join.
double maxDofRadiusPixels(int tapsPerSide);

// Reads the light accumulation (pre-exposed, either format of lighting.h) and the G-buffer depth;
// returns a new image of the same format with depth of field, which tone mapping reads.
gpu::ImageHandle addDepthOfFieldPasses(gpu::FrameGraph& graph, const FrameScene& scene,
                                       const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                       const DepthOfFieldSettings& settings);

}  // namespace obscura::passes
