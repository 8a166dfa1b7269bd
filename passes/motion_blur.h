// Motion blur (frame step 11, after depth of field; seed 000 "Motion blur"): McGuire et al. 2012's
// reconstruction filter with the seed's improvements.
//   motion_blur_tile_max       per-pixel velocity (moving draws' own from the G-buffer, the
//                              camera's from depth elsewhere), |V| and depth baked for the gather,
//                              the longest velocity of each k x k tile;
//   motion_blur_neighbour_max  the longest velocity among the tiles around each tile whose blur
//                              can reach it (3x3 for blurs up to the tile side, further for
//                              longer ones);
//   motion_blur_gather (x2)    the reconstruction filter along the neighbour max, separable: a
//                              prefilter over one step, then the whole blur over its result.
#pragma once

#include "passes/frame_scene.h"
#include "passes/frame_resources.h"

namespace obscura::passes {

// Taps per gather pass (render setting motionBlur:samples): the two passes place samples^2 along a blur.
constexpr int kMinMotionBlurSamples = 2;
constexpr int kMaxMotionBlurSamples = 32;

// The tile side (McGuire 2012's k), which was his longest blur radius (half a streak).
constexpr float kMotionBlurTileSize = 32.0f;
// The longest blur radius here: a quarter of the image's longer side, so streaks up to half the
// image keep their length (a shutter has no maximum; the neighbour max searches as many tiles as
// the radius spans), and never less than the tile side.
float motionBlurMaxRadius(uint32_t width, uint32_t height);

// Reads the light accumulation (pre-exposed, either format of lighting.h), the G-buffer's depth
// and velocity (FrameScene::motionBlur); returns a new image of the same format.
gpu::ImageHandle addMotionBlurPasses(gpu::FrameGraph& graph, const FrameScene& scene,
                                     const GBuffer& gbuffer, gpu::ImageHandle hdrColor, int samples);

}  // namespace obscura::passes
