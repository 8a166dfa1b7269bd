// Clip volumes for deferred lights (seed 004, "Deferred lighting: clip volumes"): a light that
// names a closed mesh (obscura:clipVolume) lights only the pixels whose surface lies inside it,
// so light stops at walls the artist drew the volume along. Each clip volume is rasterised into
// its own stencil bit of the G-buffer's depth/stencil target before lighting; the lighting pass
// reads the bit per light. Bits 0x01..0x40 serve up to seven clip volumes a frame; 0x80 stays
// reserved for the MSAA per-sample mask (seed 000).
#pragma once

#include "passes/frame_scene.h"
#include "passes/frame_resources.h"

namespace obscura::passes {

constexpr uint32_t kMaxClipVolumes = 7;

// Writes the clip-volume bits of `gbuffer.depth`'s stencil; returns the same image, now holding them.
// Returns the depth/stencil image (the G-buffer's) with the volumes' bits.
gpu::ImageHandle addClipVolumePass(gpu::FrameGraph& graph, const FrameScene& scene, gpu::ImageHandle depthStencil);

}  // namespace obscura::passes
