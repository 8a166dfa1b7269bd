#include "renderer/environment_cache.h"

#include <array>

namespace obscura::renderer {

EnvironmentCache::EnvironmentCache(gpu::FrameBackend& backend, VkSampler sampler)
    : backend_(backend), sampler_(sampler) {
    gpu::ImageDesc one;
    one.format = passes::kPrefilteredFormat;
    one.width = one.height = 1;
    const std::array<uint16_t, 4> black{};
    placeholder_ = backend_.createTexture(one, black.data(), sizeof(black), "no environment");
    placeholderIrradiance_ = backend_.createBufferWithData(
        nullptr, passes::kIrradianceBufferSize, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "no environment irradiance");
}

passes::EnvironmentLighting EnvironmentCache::addToFrame(gpu::FrameGraph& graph, const gpu::ImagePtr& source) {
    if (!source) {
        source_.reset();
        prefiltered_ = {};
        irradiance_.reset();
        return {graph.importTexture("environment.none", placeholder_),
                graph.importBuffer("environment.none.irradiance", placeholderIrradiance_), sampler_};
    }
    // Another texture: the maps are made again, in images that hold nothing until then.
    if (source != source_) {
        source_ = source;
        prefiltered_ = {};
    }
    if (!irradiance_)
        irradiance_ = backend_.createBuffer(passes::kIrradianceBufferSize, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            gpu::MemoryUsage::DeviceLocal, "environment irradiance");
    gpu::ImageDesc desc;
    desc.format = passes::kPrefilteredFormat;
    desc.width = passes::kPrefilteredWidth;
    desc.height = passes::kPrefilteredWidth / 2;
    desc.mipLevels = passes::kPrefilteredLevels;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    passes::EnvironmentLighting lighting{graph.importPersistent("environment.prefiltered", prefiltered_, desc),
                                         graph.importBuffer("environment.irradiance", irradiance_), sampler_};
    if (prefiltered_.holdsContents()) return lighting;
    return passes::addEnvironmentPrefilterPasses(graph, graph.importTexture("environment.source", source), lighting);
}

}  // namespace obscura::renderer
