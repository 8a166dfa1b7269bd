// AOV readback (frame step 13): packs frame resources into the render buffers the host maps,
// following Hydra's AOV conventions (include/obscura/obscura.h).
#pragma once

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

// The colour AOV's alpha is `hdrColor`'s where that holds coverage, else the G-buffer's coverage
// composited with `transparentCoverage` (passes/transparent.h).
// `velocity`: the G-buffer's velocity target, or a 1x1 image holding kStaticVelocity where the frame
// has none (the motion AOV is then the camera's motion within the shutter).
void addAovReadbackPass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gbuffer, gpu::ImageHandle hdrColor, HdrAlpha hdrAlpha,
                        gpu::ImageHandle transparentCoverage, gpu::ImageHandle display, gpu::ImageHandle velocity,
                        const std::vector<AovRequest>& requests);

}  // namespace obscura::passes
