#include "passes/occlusion_cull.h"

#include "generated/shader_layouts.h"
#include "gpu/vulkan_functions.h"
#include "passes/shader_pass.h"

#include <array>
#include <string>

namespace obscura::passes {
namespace {

// Mirrors the push constants of shaders/occlusion_cull.comp.
struct CullPush {
    uint32_t candidateCount;
    uint32_t late;
    uint32_t commandCount;
    uint32_t stamp;
    uint32_t lastStamp;
    uint32_t recordCount;
    std::array<uint32_t, 2> pixels;
};
OBSCURA_SHADER_OFFSET(CullPush, occlusion_cull_comp::Push, candidateCount);
OBSCURA_SHADER_OFFSET(CullPush, occlusion_cull_comp::Push, late);
OBSCURA_SHADER_OFFSET(CullPush, occlusion_cull_comp::Push, commandCount);
OBSCURA_SHADER_OFFSET(CullPush, occlusion_cull_comp::Push, stamp);
OBSCURA_SHADER_OFFSET(CullPush, occlusion_cull_comp::Push, lastStamp);
OBSCURA_SHADER_OFFSET(CullPush, occlusion_cull_comp::Push, recordCount);
OBSCURA_SHADER_OFFSET(CullPush, occlusion_cull_comp::Push, pixels);

constexpr uint32_t kCandidatesPerGroup = 256;

}  // namespace

gpu::BufferHandle addStampsClearPass(gpu::FrameGraph& graph, gpu::BufferHandle stamps, const std::string& name) {
    gpu::BufferHandle cleared;
    graph.addPass(
        name, gpu::PassKind::Transfer,
        [&](gpu::FrameGraph::PassBuilder& pass) { cleared = pass.write(stamps, gpu::Usage::TransferDst); },
        [stamps](VkCommandBuffer cmd, const gpu::PassResources& res) {
            vkCmdFillBuffer(cmd, res.buffer(stamps), 0, VK_WHOLE_SIZE, 0);
        });
    return cleared;
}

CulledDraws addOcclusionCullPass(gpu::FrameGraph& graph, const FrameScene& scene, CulledDraws culled,
                                 VisibilityStamps& stamps, gpu::BufferHandle pyramid) {
    const bool late = culled.phase == CulledDraws::Phase::Late;
    const bool shadows = culled.shadowViews;
    const std::array<uint32_t, 2> pixels =
        shadows ? std::array{scene.shadows.width, scene.shadows.height} : std::array{scene.width, scene.height};
    CullPush push{culled.candidateCount, late ? 1u : 0u, culled.drawCount, stamps.current, stamps.last,
                  scene.instanceCount, pixels};
    // The early phase reads the stamps; the late one tests the pyramid and stamps. Both bind
    // alike: one pipeline.
    std::vector<ShaderBinding> bindings{
        bufferRead(shadows ? scene.buffers.shadowCandidates : scene.buffers.occlusionCandidates),
        bufferReadWrite(culled.commands),
        bufferWrite(culled.lists),
        late ? bufferReadWrite(stamps.buffer) : bufferRead(stamps.buffer),
        bufferRead(shadows ? scene.buffers.shadowRecords : scene.buffers.camera),
        bufferRead(pyramid)};
    ComputePass pass{shadows ? "occlusion_cull_shadow" : "occlusion_cull", std::move(bindings), bytesOf(push)};
    pass.texels = std::array<uint32_t, 2>{culled.candidateCount, 1};
    pass.texelsPerGroup = {kCandidatesPerGroup, 1};
    pass.label = std::string(shadows ? "shadow_" : "") + (late ? "occlusion_cull_late" : "occlusion_cull_early");
    ComputeOutputs written = addComputePass(graph, std::move(pass));
    culled.commands = written.buffers[0];
    culled.lists = written.buffers[1];
    if (late) stamps.buffer = written.buffers[2];
    return culled;
}

}  // namespace obscura::passes
