#include "passes/msaa_resolve.h"

namespace obscura::passes {
namespace {

// The resolve's colour attachments: the G-buffer's targets (a velocity target with motion
// blur), then the max depth.
gpu::GraphicsPipelineDesc describeFullScreenPass(const char* fragmentShader, bool velocity) {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "fullscreen_triangle.vert";
    d.fragmentShader = fragmentShader;
    d.bindings = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    d.colorFormats = {kNormalRoughnessFormat, kAlbedoMetallicFormat, kInstanceFormat};
    if (velocity) {
        d.bindings.push_back({5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
        d.colorFormats.push_back(kVelocityFormat);
    }
    d.colorFormats.push_back(kMaxDepthFormat);
    d.depthFormat = kDepthFormat;
    return d;
}

// Sample 0 into the colour targets and, through gl_FragDepth, the depth (ALWAYS: every pixel).
gpu::GraphicsPipelineDesc describeSampleZeroPipeline(bool velocity) {
    gpu::GraphicsPipelineDesc d =
        describeFullScreenPass(velocity ? "msaa_resolve_velocity.frag" : "msaa_resolve.frag", velocity);
    d.depthCompare = VK_COMPARE_OP_ALWAYS;
    return d;
}

// The per-sample mask into the stencil's reserved bit alone (REPLACE with the bit as reference,
// under the write mask the slide gives), colour and depth untouched.
gpu::GraphicsPipelineDesc describeEdgeMaskPipeline(bool velocity) {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_edge_mask.frag", velocity);
    d.untouchedColorAttachments = (1u << d.colorFormats.size()) - 1u;
    d.depthTest = false;
    d.depthWrite = false;
    d.stencil = {true, VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_REPLACE, kMsaaEdgeStencilBit};
    return d;
}

}  // namespace

MsaaResolve addMsaaResolvePass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                               const GBuffer& multisampled) {
    MsaaResolve out{createGBufferImages(graph, scene, VK_SAMPLE_COUNT_1_BIT, "resolved"), {}};
    gpu::ImageDesc maxDepth;
    maxDepth.format = kMaxDepthFormat;
    maxDepth.width = scene.width;
    maxDepth.height = scene.height;
    out.maxDepth = graph.createImage("resolved.maxDepth", maxDepth);
    const bool velocity = multisampled.velocity.valid();
    const gpu::Pipeline& sampleZero = pipelines.get<gpu::GraphicsPipelineDesc>(
        velocity ? "msaa_resolve.velocity" : "msaa_resolve", [velocity] { return describeSampleZeroPipeline(velocity); });
    const gpu::Pipeline& edgeMask = pipelines.get<gpu::GraphicsPipelineDesc>(
        velocity ? "msaa_edge_mask.velocity" : "msaa_edge_mask", [velocity] { return describeEdgeMaskPipeline(velocity); });
    gpu::Device& device = pipelines.device();
    const GBuffer& resolved = out.resolved;

    graph.addPass(
        "msaa_resolve", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(multisampled.depth, gpu::Usage::SampledFragment);
            pass.read(multisampled.normalRoughness, gpu::Usage::SampledFragment);
            pass.read(multisampled.albedoMetallic, gpu::Usage::SampledFragment);
            pass.read(multisampled.instance, gpu::Usage::SampledFragment);
            if (velocity) pass.read(multisampled.velocity, gpu::Usage::SampledFragment);
            // The stencil clear happens here, so the edge bit is set again right after it (seed 000:
            // "restore whenever a stencil clear occurs"); clip volumes add their bits later.
            pass.depthStencilAttachment(resolved.depth, VkClearDepthStencilValue{1.0f, 0});
            pass.colorAttachment(resolved.normalRoughness);
            pass.colorAttachment(resolved.albedoMetallic);
            pass.colorAttachment(resolved.instance);
            if (velocity) pass.colorAttachment(resolved.velocity);
            pass.colorAttachment(out.maxDepth);
        },
        [&device, &sampleZero, &edgeMask, &scene, multisampled, velocity](VkCommandBuffer cmd,
                                                                         const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            for (const gpu::Pipeline* pipeline : {&sampleZero, &edgeMask}) {
                gpu::DescriptorWriter writer(device, *pipeline);
                writer.sampled(0, res.view(multisampled.depth), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                    .sampled(1, res.view(multisampled.normalRoughness), nearest)
                    .sampled(2, res.view(multisampled.albedoMetallic), nearest)
                    .sampled(3, res.view(multisampled.instance), nearest)
                    .buffer(4, scene.camera->buffer);
                if (velocity) writer.sampled(5, res.view(multisampled.velocity), nearest);
                writer.bind(cmd);
                if (pipeline == &edgeMask)
                    vkCmdSetStencilWriteMask(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, kMsaaEdgeStencilBit);
                vkCmdDraw(cmd, 3, 1, 0, 0);
            }
        });
    return out;
}

}  // namespace obscura::passes
