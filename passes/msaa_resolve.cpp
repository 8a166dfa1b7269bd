#include "passes/msaa_resolve.h"

namespace obscura::passes {
namespace {

const std::vector<gpu::BindingDesc> kResolveBindings = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                        {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                        {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                        {4, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}};

gpu::GraphicsPipelineDesc describeFullScreenPass(const char* fragmentShader) {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "fullscreen_triangle.vert";
    d.fragmentShader = fragmentShader;
    d.bindings = kResolveBindings;
    d.colorFormats = {kNormalRoughnessFormat, kAlbedoMetallicFormat, kInstanceFormat};
    d.depthFormat = kDepthFormat;
    return d;
}

// Sample 0 into the colour targets and, through gl_FragDepth, the depth (ALWAYS: every pixel).
gpu::GraphicsPipelineDesc describeSampleZeroPipeline() {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_resolve.frag");
    d.depthCompare = VK_COMPARE_OP_ALWAYS;
    return d;
}

// The per-sample mask into the stencil's reserved bit alone (REPLACE with the bit as reference,
// under the write mask the slide gives), colour and depth untouched.
gpu::GraphicsPipelineDesc describeEdgeMaskPipeline() {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_edge_mask.frag");
    d.colorWrite = false;
    d.depthTest = false;
    d.depthWrite = false;
    d.stencil = {true, VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_REPLACE, kMsaaEdgeStencilBit};
    return d;
}

}  // namespace

GBuffer addMsaaResolvePass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                           const GBuffer& multisampled) {
    GBuffer resolved = createGBufferImages(graph, scene, VK_SAMPLE_COUNT_1_BIT, "resolved");
    const gpu::Pipeline& sampleZero =
        pipelines.get<gpu::GraphicsPipelineDesc>("msaa_resolve", describeSampleZeroPipeline);
    const gpu::Pipeline& edgeMask =
        pipelines.get<gpu::GraphicsPipelineDesc>("msaa_edge_mask", describeEdgeMaskPipeline);
    gpu::Device& device = pipelines.device();

    graph.addPass(
        "msaa_resolve", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(multisampled.depth, gpu::Usage::SampledFragment);
            pass.read(multisampled.normalRoughness, gpu::Usage::SampledFragment);
            pass.read(multisampled.albedoMetallic, gpu::Usage::SampledFragment);
            pass.read(multisampled.instance, gpu::Usage::SampledFragment);
            // The stencil clear happens here, so the edge bit is set again right after it (seed 000:
            // "restore whenever a stencil clear occurs"); clip volumes add their bits later.
            pass.depthStencilAttachment(resolved.depth, VkClearDepthStencilValue{1.0f, 0});
            pass.colorAttachment(resolved.normalRoughness);
            pass.colorAttachment(resolved.albedoMetallic);
            pass.colorAttachment(resolved.instance);
        },
        [&device, &sampleZero, &edgeMask, &scene, multisampled](VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            for (const gpu::Pipeline* pipeline : {&sampleZero, &edgeMask}) {
                gpu::DescriptorWriter(device, *pipeline)
                    .sampled(0, res.view(multisampled.depth), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                    .sampled(1, res.view(multisampled.normalRoughness), nearest)
                    .sampled(2, res.view(multisampled.albedoMetallic), nearest)
                    .sampled(3, res.view(multisampled.instance), nearest)
                    .buffer(4, scene.camera->buffer)
                    .bind(cmd);
                if (pipeline == &edgeMask)
                    vkCmdSetStencilWriteMask(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, kMsaaEdgeStencilBit);
                vkCmdDraw(cmd, 3, 1, 0, 0);
            }
        });
    return resolved;
}

}  // namespace obscura::passes
