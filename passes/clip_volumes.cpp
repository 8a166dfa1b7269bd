#include "passes/clip_volumes.h"

#include "gpu/vulkan_functions.h"
#include "passes/depth_only_draw.h"
#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

// Inside-ness by parity: a closed surface crosses the view ray behind a point an odd number of
// times exactly when the point is inside it, whatever its shape and wherever the camera is. Every
// face fragment behind the G-buffer's depth (depth test GREATER, no depth write, no culling)
// inverts the volume's bit, so the bit ends set for surfaces inside. (The classic stencil light
// volume needs a convex volume; parity takes concave rooms too.)
gpu::GraphicsPipelineDesc describeClipVolumePipeline(const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d = describeDepthOnlyDraw();
    d.bindings = bindingLayout(bindings);
    d.depthFormat = kDepthFormat;
    d.depthWrite = false;
    d.depthCompare = VK_COMPARE_OP_GREATER;
    d.stencil = {true, VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_INVERT};
    return d;
}

}  // namespace

gpu::ImageHandle addClipVolumePass(gpu::FrameGraph& graph, const FrameScene& scene, gpu::ImageHandle depthStencil) {
    if (scene.clipVolumes.empty()) return depthStencil;
    const std::vector<ShaderBinding> bindings{bufferRead(scene.buffers.instances)};
    const gpu::PipelineCache::Request pipelineRequest = gpu::PipelineCache::request<gpu::GraphicsPipelineDesc>(
        "clip_volumes", [bindings] { return describeClipVolumePipeline(bindings); });
    graph.addPass(
        "clip_volumes", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.usesPipeline(pipelineRequest);
            declareBindings(pass, bindings, ShaderStage::Graphics);
            depthStencil = pass.depthStencilAttachment(depthStencil);
        },
        [&scene, bindings, pipelineRequest](VkCommandBuffer cmd, const gpu::PassResources& res) {
            const gpu::Pipeline& pipeline = res.pipelines().get(pipelineRequest);
            bindBindings(cmd, pipeline, bindings, res);
            for (const ClipVolume& volume : scene.clipVolumes) {
                vkCmdSetStencilWriteMask(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, volume.stencilBit);
                recordDepthOnlyDraw(cmd, pipeline, volume.draw, {scene.cameraData.viewProjection, 0});
            }
        });
    return depthStencil;
}

}  // namespace obscura::passes
