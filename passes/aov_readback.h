// AOV readback (frame step 13, with step 12 folded in): packs frame resources into the render
// buffers the host maps, following Hydra's AOV conventions (include/obscura/obscura.h). The display
// AOV is the HDR colour through the OCIO display/view transform baked into a 3D LUT behind a log2
// shaper (seed 004 "Color grading"), applied as it is packed: the frame's last pass tone maps, and
// no display image is written and read again between.
#pragma once

#include "pass_support/color_grading_lut.h"
#include "passes/frame_resources.h"
#include "passes/hdr_color.h"

#include <vector>

namespace obscura::passes {

enum class Aov : uint32_t {
    Color = 0,
    Depth = 1,
    Normal = 2,
    Albedo = 3,
    PrimId = 4,
    Display = 5,
    Motion = 6,
    InstanceId = 7
};

struct AovRequest {
    Aov aov;
    gpu::BufferPtr destination;  // host-visible; width * height elements of the AOV's format
    gpu::BufferPtr deviceStaging;  // optional device-local twin: packed there, then copied
};

// The colour and display AOVs' alpha is `hdrColor`'s where that holds coverage, else the G-buffer's
// coverage composited with `transparentCoverage` (passes/transparent.h).
// `velocity`: the G-buffer's velocity target, or a 1x1 image holding kStaticVelocity where the frame
// has none (the motion AOV is then the camera's motion within the shutter).
void addAovReadbackPass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gbuffer, gpu::ImageHandle hdrColor, HdrAlpha hdrAlpha,
                        gpu::ImageHandle transparentCoverage, const ColorGradingLut& grading, gpu::ImageHandle velocity,
                        const std::vector<AovRequest>& requests);

}  // namespace obscura::passes
