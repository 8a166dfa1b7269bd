#include "passes/msaa_resolve.h"

#include "gpu/vulkan_functions.h"
#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

// What both pipelines of the resolve read: the multisampled G-buffer (its velocity target with
// motion blur) and the camera.
std::vector<ShaderBinding> resolveBindings(const FrameScene& scene, const GBuffer& multisampled) {
    std::vector<ShaderBinding> bindings{sampled(multisampled.depth), sampled(multisampled.normalRoughness),
                                        sampled(multisampled.albedoMetallic), sampled(multisampled.instance),
                                        bufferRead(scene.buffers.camera)};
    if (multisampled.velocity.valid()) bindings.push_back(sampled(multisampled.velocity));
    return bindings;
}

// The resolve's colour attachments: the G-buffer's targets (a velocity target with motion
// blur), then the max depth.
gpu::GraphicsPipelineDesc describeFullScreenPass(const char* fragmentShader, const std::vector<ShaderBinding>& bindings,
                                                 bool velocity) {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "fullscreen_triangle.vert";
    d.fragmentShader = fragmentShader;
    d.bindings = bindingLayout(bindings);
    d.colorFormats = {kNormalRoughnessFormat, kAlbedoMetallicFormat, kInstanceFormat};
    if (velocity) d.colorFormats.push_back(kVelocityFormat);
    d.colorFormats.push_back(kMaxDepthFormat);
    d.depthFormat = kDepthFormat;
    return d;
}

// Sample 0 into the colour targets and, through gl_FragDepth, the depth (ALWAYS: every pixel).
gpu::GraphicsPipelineDesc describeSampleZeroPipeline(const std::vector<ShaderBinding>& bindings, bool velocity) {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass(
        velocity ? "msaa_resolve_velocity.frag" : "msaa_resolve.frag", bindings, velocity);
    d.depthCompare = VK_COMPARE_OP_ALWAYS;
    return d;
}

// The per-sample mask into the stencil's reserved bit alone (REPLACE with the bit as reference,
// under the write mask the slide gives), colour and depth untouched.
gpu::GraphicsPipelineDesc describeEdgeMaskPipeline(const std::vector<ShaderBinding>& bindings, bool velocity) {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_edge_mask.frag", bindings, velocity);
    d.untouchedColorAttachments = (1u << d.colorFormats.size()) - 1u;
    d.depthTest = false;
    d.depthWrite = false;
    d.stencil = {true, VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_REPLACE, kMsaaEdgeStencilBit};
    return d;
}

}  // namespace

MsaaResolve addMsaaResolvePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& multisampled) {
    MsaaResolve out{createGBufferImages(graph, scene, VK_SAMPLE_COUNT_1_BIT, "resolved"),
                    graph.createImage("resolved.maxDepth", imageDesc2D(kMaxDepthFormat, scene.width, scene.height))};
    const bool velocity = multisampled.velocity.valid();
    std::vector<ShaderBinding> bindings = resolveBindings(scene, multisampled);
    GBuffer& resolved = out.resolved;
    graph.addPass(
        "msaa_resolve", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            declareBindings(pass, bindings, ShaderStage::Graphics);
            // The stencil clear happens here, so the edge bit is set again right after it (seed 000:
            // "restore whenever a stencil clear occurs"); clip volumes add their bits later.
            resolved.depth = pass.depthStencilAttachment(resolved.depth, VkClearDepthStencilValue{1.0f, 0});
            // The sample-0 copy writes every texel of every colour target.
            const auto overwritten = gpu::FrameGraph::PassBuilder::Load::Discard;
            resolved.normalRoughness = pass.colorAttachment(resolved.normalRoughness, overwritten);
            resolved.albedoMetallic = pass.colorAttachment(resolved.albedoMetallic, overwritten);
            resolved.instance = pass.colorAttachment(resolved.instance, overwritten);
            if (velocity) resolved.velocity = pass.colorAttachment(resolved.velocity, overwritten);
            out.maxDepth = pass.colorAttachment(out.maxDepth, overwritten);
        },
        [bindings, velocity](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::PipelineCache& pipelines = res.pipelines();
            const gpu::Pipeline& sampleZero = pipelines.get<gpu::GraphicsPipelineDesc>(
                velocity ? "msaa_resolve.velocity" : "msaa_resolve",
                [&] { return describeSampleZeroPipeline(bindings, velocity); });
            const gpu::Pipeline& edgeMask = pipelines.get<gpu::GraphicsPipelineDesc>(
                velocity ? "msaa_edge_mask.velocity" : "msaa_edge_mask",
                [&] { return describeEdgeMaskPipeline(bindings, velocity); });
            for (const gpu::Pipeline* pipeline : {&sampleZero, &edgeMask}) {
                bindBindings(cmd, *pipeline, bindings, res);
                if (pipeline == &edgeMask)
                    vkCmdSetStencilWriteMask(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, kMsaaEdgeStencilBit);
                vkCmdDraw(cmd, 3, 1, 0, 0);
            }
        });
    return out;
}

}  // namespace obscura::passes
