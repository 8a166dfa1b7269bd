#include "renderer/gpu_occlusion_culling.h"

#include "passes/buffer_copy.h"
#include "passes/gbuffer.h"
#include "passes/hi_z.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace obscura::renderer {

gpu::BufferPtr& GpuOcclusionCulling::sized(gpu::BufferPtr& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                                           gpu::MemoryUsage memory, const char* name) {
    // A buffer never holds less than one element: bindings need a resource.
    bytes = std::max<VkDeviceSize>(bytes, 16);
    if (!buffer || buffer->size < bytes) buffer = backend_.createBuffer(bytes, usage, memory, name);
    return buffer;
}

passes::CulledDraws GpuOcclusionCulling::addEarlyCulling(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                                         Route& route, passes::CulledDraws culled,
                                                         const std::vector<passes::CulledDrawCommand>& commands,
                                                         const Route::Key& key, passes::VisibilityStamps& stamps,
                                                         uint32_t width, uint32_t height,
                                                         gpu::BufferHandle& pyramid) {
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    // Resources and passes of the shadow views' route are named apart from the camera's.
    const std::string prefix = culled.shadowViews ? "shadow_" : "";
    // The stamps: a change to the records makes the last frame's meaningless, and the early phase
    // then draws every candidate. A new buffer is cleared within the frame (0 is never a stamp).
    const VkDeviceSize stampBytes = std::max<VkDeviceSize>(key.stampCount, 1) * sizeof(uint32_t);
    const bool made = !route.stamps || route.stamps->size < stampBytes;
    if (made) {
        route.stamps = backend_.createBuffer(stampBytes, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                             gpu::MemoryUsage::DeviceLocal, (prefix + "visibility stamps").c_str());
        route.stamped.reset();
    }
    stamps.last = route.stamped == key ? route.lastStamp : 0;
    stamps.current = route.lastStamp + 1 == 0 ? 1 : route.lastStamp + 1;
    route.lastStamp = stamps.current;
    route.stamped = key;
    stamps.buffer = graph.importBuffer(prefix + "visibilityStamps", route.stamps);
    if (made) stamps.buffer = passes::addStampsClearPass(graph, stamps.buffer, prefix + "occlusion_stamps_clear");

    // Each culled draw's commands, with no instance counted: the early phase's, then the late one's,
    // copied into device-local memory where the culling passes count.
    std::vector<passes::CulledDrawCommand> both(commands);
    for (passes::CulledDrawCommand late : commands) {
        late.listOffset += culled.candidateCount;
        both.push_back(late);
    }
    const VkDeviceSize commandBytes = both.size() * sizeof(passes::CulledDrawCommand);
    std::vector<uint8_t> bytes(commandBytes);
    std::memcpy(bytes.data(), both.data(), commandBytes);
    sized(route.commands, commandBytes,
          storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
              VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
          gpu::MemoryUsage::DeviceLocal, "culled draw commands");
    culled.phase = passes::CulledDraws::Phase::Early;
    culled.commands = passes::addBufferCopyPass(
        graph, prefix + "occlusion_commands", graph.createBuffer(prefix + "commandsOfTheHost", std::move(bytes)),
        graph.importBuffer(prefix + "culledDrawCommands", route.commands), commandBytes);
    culled.lists = graph.importBuffer(
        prefix + "culledDrawLists",
        sized(route.lists, VkDeviceSize(2) * culled.candidateCount * sizeof(uint32_t), storage,
              gpu::MemoryUsage::DeviceLocal, "culled draw lists"));
    pyramid = graph.importBuffer(prefix + "hiZPyramid",
                                 sized(route.pyramid, passes::hiZPyramidFloats(width, height) * sizeof(float), storage,
                                       gpu::MemoryUsage::DeviceLocal, "depth pyramid"));
    return passes::addOcclusionCullPass(graph, scene, culled, stamps, pyramid);
}

passes::GBuffer GpuOcclusionCulling::addGBuffer(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                                const Versions& versions, gpu::ImageHandle bestFitNormals,
                                                VkSampleCountFlagBits samples, bool alphaToCoverage) {
    passes::CulledDraws culled;
    culled.drawCount = scene.gpuCulledDraws;
    culled.candidateCount = scene.occlusionCandidateCount;
    std::vector<passes::CulledDrawCommand> commands(culled.drawCount);
    for (const passes::Draw& draw : scene.cameraDraws)
        if (draw.culledOnGpu())
            commands[draw.cullSlot] = {draw.indexCount, 0, draw.firstIndex, 0, 0, culled.listOffset(draw.firstCandidate)};
    passes::VisibilityStamps stamps;
    gpu::BufferHandle pyramid;
    culled = addEarlyCulling(graph, scene, camera_, culled, commands, {versions, scene.instanceCount}, stamps,
                             scene.width, scene.height, pyramid);
    passes::GBuffer gbuffer = passes::addGBufferPass(graph, scene, bestFitNormals, samples, alphaToCoverage, &culled);
    pyramid = passes::addHiZPasses(graph, gbuffer.depth, pyramid);
    culled.phase = passes::CulledDraws::Phase::Late;
    culled = passes::addOcclusionCullPass(graph, scene, culled, stamps, pyramid);
    gbuffer = passes::addGBufferLatePass(graph, scene, gbuffer, bestFitNormals, samples, alphaToCoverage, culled);
    // The counts come back to the host once the frame ran (culled()).
    const VkDeviceSize commandBytes = VkDeviceSize(2) * culled.drawCount * sizeof(passes::CulledDrawCommand);
    sized(camera_.counted, commandBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback,
          "culled draw counts");
    graph.markOutput(passes::addBufferCopyPass(graph, "occlusion_counts", culled.commands,
                                               graph.importBuffer("culledDrawCounts", camera_.counted), commandBytes));
    return gbuffer;
}

gpu::ImageHandle GpuOcclusionCulling::addShadowMaps(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                                    const Versions& versions, passes::ShadowAtlasHistory& history) {
    const passes::ShadowAtlas& atlas = scene.shadows;
    passes::CulledDraws culled;
    culled.shadowViews = true;
    culled.drawCount = atlas.gpuCulledDraws;
    culled.candidateCount = atlas.occlusionCandidateCount;
    std::vector<passes::CulledDrawCommand> commands(culled.drawCount);
    for (uint32_t v = 0; v < atlas.views.size(); ++v) {
        const passes::ShadowMapView& view = atlas.views[v];
        for (size_t i = 0; i < view.culled.size(); ++i) {
            const passes::CulledViewDraw& c = view.culled[i];
            if (c.cullSlot == passes::Draw::kNotCulledOnGpu) continue;
            const passes::Draw& draw = scene.draws[view.draws[i]];
            commands[c.cullSlot] = {draw.indexCount, 0, draw.firstIndex, 0, 0, culled.listOffset(c.firstCandidate), v};
        }
    }
    // No view changed: the kept atlas is read as it is, and nothing is culled.
    passes::ShadowMapRender early = passes::planShadowMaps(graph, scene, &history);
    if (!early.rendered) return early.atlas;
    passes::VisibilityStamps stamps;
    gpu::BufferHandle pyramid;
    const uint64_t stampCount = uint64_t(atlas.views.size()) * scene.instanceCount;
    culled = addEarlyCulling(graph, scene, shadows_, culled, commands, {versions, stampCount}, stamps, atlas.width,
                             atlas.height, pyramid);
    passes::addShadowMapEarlyPass(graph, scene, early, culled);
    pyramid = passes::addHiZPasses(graph, early.atlas, pyramid, "shadow_hi_z");
    culled.phase = passes::CulledDraws::Phase::Late;
    culled = passes::addOcclusionCullPass(graph, scene, culled, stamps, pyramid);
    return passes::addShadowMapLatePass(graph, scene, early, culled);
}

GpuOcclusionCulling::Culled GpuOcclusionCulling::culled(const passes::FrameScene& scene) const {
    Culled result;
    if (scene.gpuCulledDraws == 0 || !camera_.counted) return result;
    const auto* commands = static_cast<const passes::CulledDrawCommand*>(camera_.counted->mapped());
    for (const passes::Draw& draw : scene.cameraDraws) {
        if (!draw.culledOnGpu()) continue;
        const uint64_t drawn = uint64_t(commands[draw.cullSlot].instanceCount) +
                               commands[scene.gpuCulledDraws + draw.cullSlot].instanceCount;
        const uint64_t left = draw.instanceCount - std::min<uint64_t>(drawn, draw.instanceCount);
        result.instances += left;
        result.triangles += left * (draw.indexCount / 3);
        if (drawn == 0) result.draws += 1;
    }
    return result;
}

}  // namespace obscura::renderer
