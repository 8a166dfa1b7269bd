#include "renderer/environment_cache.h"

#include <algorithm>
#include <array>

namespace obscura::renderer {

EnvironmentCache::EnvironmentCache(gpu::Device& device, VkSampler sampler) : device_(device), sampler_(sampler) {
    gpu::ImageDesc one;
    one.format = passes::kPrefilteredFormat;
    one.width = one.height = 1;
    const std::array<uint16_t, 4> black{};
    placeholder_ = device_.createTextureWithData(one, black.data(), sizeof(black), "no environment");
    placeholderIrradiance_ = device_.createBufferWithData(nullptr, passes::kIrradianceBufferSize,
                                                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "no environment irradiance");
}

passes::EnvironmentLighting EnvironmentCache::addToFrame(gpu::FrameGraph& graph, const gpu::ImagePtr& source) {
    pending_.reset();
    prefilteredHandle_ = {};
    if (!source) {
        source_.reset();
        prefiltered_.reset();
        irradiance_.reset();
        prefilteredLayout_ = VK_IMAGE_LAYOUT_UNDEFINED;
        return {graph.importImage("environment.none", placeholder_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL),
                graph.importBuffer("environment.none.irradiance", placeholderIrradiance_), sampler_};
    }
    if (!prefiltered_) {
        gpu::ImageDesc desc;
        desc.format = passes::kPrefilteredFormat;
        desc.width = passes::kPrefilteredWidth;
        desc.height = passes::kPrefilteredWidth / 2;
        desc.mipLevels = passes::kPrefilteredLevels;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        prefiltered_ = device_.createImage(desc, "prefiltered environment");
        irradiance_ = device_.createBuffer(passes::kIrradianceBufferSize, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           gpu::MemoryUsage::DeviceLocal, "environment irradiance");
        prefilteredLayout_ = VK_IMAGE_LAYOUT_UNDEFINED;
    }
    passes::EnvironmentLighting lighting{graph.importImage("environment.prefiltered", prefiltered_, prefilteredLayout_),
                                         graph.importBuffer("environment.irradiance", irradiance_), sampler_};
    prefilteredHandle_ = lighting.prefiltered;
    if (source != source_) {
        gpu::ImageHandle texture =
            graph.importImage("environment.source", source, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        lighting = passes::addEnvironmentPrefilterPasses(graph, texture, lighting);
        pending_ = source;
    }
    return lighting;
}

void EnvironmentCache::frameCompiled(const gpu::FrameGraph& graph) {
    if (!prefilteredHandle_.valid()) return;
    prefilteredLayout_ = graph.finalLayout(prefilteredHandle_);
    if (!pending_) return;
    const auto& passes = graph.compiled();
    bool prefiltered = std::any_of(passes.begin(), passes.end(), [](const gpu::FrameGraph::CompiledPass& pass) {
        return pass.name == passes::kEnvironmentPrefilterPass && !pass.culled;
    });
    if (prefiltered) source_ = pending_;
}

}  // namespace obscura::renderer
