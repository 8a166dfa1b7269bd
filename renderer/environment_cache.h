// The textured dome's prefiltered lighting (passes/environment_prefilter.h), kept across frames:
// the prefilter passes run in the frame after the dome's texture changes and never otherwise.
// The maps are in the dome's own frame, so a new transform needs no prefiltering (the lighting
// pass rotates its lookups).
#pragma once

#include "gpu/frame_backend.h"
#include "gpu/history_images.h"
#include "passes/environment_prefilter.h"

namespace obscura::renderer {

class EnvironmentCache {
public:
    // `sampler` reads the source and the prefiltered chain: trilinear, repeating in longitude
    // and clamped in latitude.
    EnvironmentCache(gpu::FrameBackend& backend, VkSampler sampler);

    // Imports the frame's environment resources into `graph`, with the prefilter passes when the
    // maps do not hold `source` (the dome's latlong texture) yet. Without a source: placeholders
    // (a 1x1 black image, zero coefficients), and the maps are released.
    passes::EnvironmentLighting addToFrame(gpu::FrameGraph& graph, const gpu::ImagePtr& source);

private:
    gpu::FrameBackend& backend_;
    VkSampler sampler_;
    // The texture the maps are made from; they hold it once a frame that prefiltered it ran.
    gpu::ImagePtr source_;
    gpu::PersistentImage prefiltered_;
    gpu::BufferPtr irradiance_;
    gpu::ImagePtr placeholder_;
    gpu::BufferPtr placeholderIrradiance_;
};

}  // namespace obscura::renderer
