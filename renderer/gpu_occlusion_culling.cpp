#include "renderer/gpu_occlusion_culling.h"

#include "passes/gbuffer.h"
#include "passes/hi_z.h"
#include "passes/occlusion_cull.h"

#include <cstring>
#include <vector>

namespace obscura::renderer {

gpu::BufferPtr& GpuOcclusionCulling::sized(gpu::BufferPtr& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                                           gpu::MemoryUsage memory, const char* name) {
    // A buffer never holds less than one element: bindings need a resource.
    bytes = std::max<VkDeviceSize>(bytes, 16);
    if (!buffer || buffer->size < bytes) buffer = backend_.createBuffer(bytes, usage, memory, name);
    return buffer;
}

passes::GBuffer GpuOcclusionCulling::addGBuffer(gpu::FrameGraph& graph, const passes::FrameScene& scene,
                                                const RecordsKey& key, gpu::ImageHandle bestFitNormals,
                                                VkSampleCountFlagBits samples, bool alphaToCoverage) {
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    // The stamps: zeros (never a frame's stamp) when made again; a change to the records makes the
    // last frame's meaningless, and the early phase then draws every candidate.
    const VkDeviceSize stampBytes = VkDeviceSize(std::max(scene.instanceCount, 1u)) * sizeof(uint32_t);
    const bool made = !stamps_ || stamps_->size < stampBytes;
    if (made) {
        stamps_ = backend_.createBuffer(stampBytes, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        gpu::MemoryUsage::DeviceLocal, "visibility stamps");
        stamped_.reset();
    }
    passes::VisibilityStamps stamps;
    stamps.last = stamped_ == key ? lastStamp_ : 0;
    stamps.current = lastStamp_ + 1 == 0 ? 1 : lastStamp_ + 1;
    lastStamp_ = stamps.current;
    stamped_ = key;
    stamps.buffer = graph.importBuffer("visibilityStamps", stamps_);
    // A new buffer is cleared within the frame (0 is never a frame's stamp).
    if (made) stamps.buffer = passes::addStampsClearPass(graph, stamps.buffer);

    // Each culled draw's commands, with no instance counted: the early phase's, then the late one's.
    passes::CulledDraws culled;
    culled.drawCount = scene.gpuCulledDraws;
    culled.candidateCount = scene.occlusionCandidateCount;
    sized(commands_, VkDeviceSize(2) * culled.drawCount * sizeof(passes::CulledDrawCommand),
          storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, gpu::MemoryUsage::Readback, "culled draw commands");
    auto* commands = static_cast<passes::CulledDrawCommand*>(commands_->mapped());
    for (const passes::Draw& draw : scene.cameraDraws) {
        if (!draw.culledOnGpu()) continue;
        for (auto phase : {passes::CulledDraws::Phase::Early, passes::CulledDraws::Phase::Late}) {
            culled.phase = phase;
            commands[culled.command(draw)] = {draw.indexCount, 0, draw.firstIndex, 0, 0, culled.listOffset(draw)};
        }
    }
    culled.phase = passes::CulledDraws::Phase::Early;
    culled.commands = graph.importBuffer("culledDrawCommands", commands_);
    culled.lists = graph.importBuffer(
        "culledDrawLists", sized(lists_, VkDeviceSize(2) * culled.candidateCount * sizeof(uint32_t), storage,
                                 gpu::MemoryUsage::DeviceLocal, "culled draw lists"));
    gpu::BufferHandle pyramid = graph.importBuffer(
        "hiZPyramid", sized(pyramid_, passes::hiZPyramidFloats(scene.width, scene.height) * sizeof(float), storage,
                            gpu::MemoryUsage::DeviceLocal, "depth pyramid"));

    culled = passes::addOcclusionCullPass(graph, scene, culled, stamps, pyramid);
    passes::GBuffer gbuffer = passes::addGBufferPass(graph, scene, bestFitNormals, samples, alphaToCoverage, &culled);
    pyramid = passes::addHiZPasses(graph, gbuffer.depth, pyramid);
    culled.phase = passes::CulledDraws::Phase::Late;
    culled = passes::addOcclusionCullPass(graph, scene, culled, stamps, pyramid);
    // The counts come back to the host once the frame ran (culled()).
    graph.markOutput(culled.commands);
    return passes::addGBufferLatePass(graph, scene, gbuffer, bestFitNormals, samples, alphaToCoverage, culled);
}

GpuOcclusionCulling::Culled GpuOcclusionCulling::culled(const passes::FrameScene& scene) const {
    Culled result;
    if (scene.gpuCulledDraws == 0 || !commands_) return result;
    const auto* commands = static_cast<const passes::CulledDrawCommand*>(commands_->mapped());
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
