// Depth of field (frame step 10; seed 000 "Depth of field"): a physically based circle of
// confusion from the camera's lens, and the separable flexible filter at half resolution (or full,
// FieldResolution).
//   dof_downsample  CoC per pixel (one multiply-add), bilateral downscale of the near and far
//                   fields, each premultiplied by its CoC (R11G11B10F), and the fields' CoC (R8G8:
//                   near, far); a workgroup a tile, which also writes the tile's CoC: the near
//                   field's max and the far field's max (the min of the signed CoC, whose far
//                   field is negative);
//   dof_gather      a workgroup a tile: the near max over the tiles a near CoC can reach from
//                   (scatter as gather), written for the composite too; then the first pass, N^2
//                   taps (7x7) for both fields, branching on the tiles;
//   dof_flood_fill  second pass, 3x3 taps a third of the first pass's spacing apart, averaged:
//                   together the two passes sample the kernel on a 3N x 3N grid;
//   dof_composite   far field upscaled bilaterally, near field freely, both with bicubic weights
//                   (Sigg & Hadwiger 2005), blended non-linearly over the sharp image.
// A pass's dispatch and wait cost more than the tile steps fused into the downsample and gather.
#pragma once

#include "passes/frame_resources.h"
#include "pass_support/thin_lens.h"

namespace obscura::passes {

// Taps per side of the first gather pass: 7 (49 taps) as the seed; more is a quality setting.
constexpr int kDefaultDofTapsPerSide = 7;
constexpr int kMinDofTapsPerSide = 3;
constexpr int kMaxDofTapsPerSide = 15;

// Where the filter runs. Half resolution is the seed's (a quarter of the taps' cost). A still's
// sample spreads over its cell of the aperture alone, a few pixels: there the half-resolution
// chain's own blur (a standard deviation of 1.5 pixels) would soften the edges of every bokeh
// beyond the pixel box the reference has, so it runs at full resolution (DepthOfFieldConvergence
// tests, bright-point bokeh against 4096 reference sub-frames: 40.4 -> 41.8 dB round, 39.5 -> 41.0
// dB with 6 blades; the planes unchanged; a 640x360 still of scenes/depth_of_field.usda no slower).
enum class FieldResolution { Half, Full };

struct DepthOfFieldSettings {
    CocFromDepth coc;        // signed CoC radius in pixels from device depth
    ApertureShape aperture;
    // The part of the aperture the blur spans: all of it in a real-time frame; a still's sample
    // spreads over its own cell (renderer/reference_frames.h stillLensSample).
    ApertureCell cell;
    // Where the frame's image lies shifted (temporal AA's jitter, pixels, x right, y down): the
    // blurred fields are read where the unshifted image lies, so that the cells of a still's
    // samples, each taken with its own jitter, meet where they join; the sharp pixels keep it.
    std::array<double, 2> jitter{0.0, 0.0};
    int tapsPerSide = kDefaultDofTapsPerSide;
    FieldResolution resolution = FieldResolution::Half;
};

// The largest radius the filter's kernel reaches, in full-resolution pixels ("limit offset range to
// minimize undersampling"): the two passes place N^2 x 9 points over the aperture; at a radius of
// 2N half-resolution texels they lie about one texel apart, which bilinear fetches still join. A
// cell's kernel spans its share of the CoC, so a still's samples clamp the CoC at this over the
// share.
double maxDofRadiusPixels(int tapsPerSide);

// Reads the light accumulation (pre-exposed, either format of lighting.h) and the G-buffer depth;
// returns a new image of the same format with depth of field, which tone mapping reads.
gpu::ImageHandle addDepthOfFieldPasses(gpu::FrameGraph& graph, const FrameScene& scene,
                                       const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                       const DepthOfFieldSettings& settings);

}  // namespace obscura::passes
