// The textured dome's prefiltered lighting (passes/environment_prefilter.h), kept across frames:
// the prefilter passes run in the frame after the dome's texture changes and never otherwise.
// The maps are in the dome's own frame, so a new transform needs no prefiltering (the lighting
// pass rotates its lookups).
#pragma once

#include "passes/environment_prefilter.h"

namespace obscura::renderer {

class EnvironmentCache {
public:
    // `sampler` reads the source and the prefiltered chain: trilinear, repeating in longitude
    // and clamped in latitude.
    EnvironmentCache(gpu::Device& device, VkSampler sampler);

    // Imports the frame's environment resources into `graph` and adds the prefilter passes when
    // `source` (the dome's latlong texture) is not the image the maps were made from. Without a source: placeholders (a
    // 1x1 black image, zero coefficients), and the maps are released.
    passes::EnvironmentLighting addToFrame(gpu::FrameGraph& graph, const gpu::ImagePtr& source);
    // After graph.compile(): remembers the layout the frame leaves the maps in, and which texture
    // they now hold (unless the graph culled the prefilter).
    void frameCompiled(const gpu::FrameGraph& graph);

private:
    gpu::Device& device_;
    VkSampler sampler_;
    gpu::ImagePtr source_;   // what the maps hold
    gpu::ImagePtr pending_;  // what this frame's prefilter writes into them
    gpu::ImagePtr prefiltered_;
    VkImageLayout prefilteredLayout_ = VK_IMAGE_LAYOUT_UNDEFINED;
    gpu::ImageHandle prefilteredHandle_;
    gpu::BufferPtr irradiance_;
    gpu::ImagePtr placeholder_;
    gpu::BufferPtr placeholderIrradiance_;
};

}  // namespace obscura::renderer
