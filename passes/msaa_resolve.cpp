#include "passes/msaa_resolve.h"

#include "gpu/vulkan_functions.h"
#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

// The depth msaa_resolve.comp chose per pixel, for the raster draw that writes the depth target.
constexpr VkFormat kCentreDepthFormat = VK_FORMAT_R32_SFLOAT;
// 1 where the pixel's 2x2 quad holds a pixel whose samples differ.
constexpr VkFormat kEdgeQuadsFormat = VK_FORMAT_R8_UNORM;

// Both draws of the raster half: the depth target and sample 0 of the sRGB albedo, then the
// tagged quads' stencil bit.
gpu::GraphicsPipelineDesc describeFullScreenPass(const char* fragmentShader, const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "fullscreen_triangle.vert";
    d.fragmentShader = fragmentShader;
    d.bindings = bindingLayout(bindings);
    d.colorFormats = {kAlbedoMetallicFormat};
    d.depthFormat = kDepthFormat;
    return d;
}

// The chosen depth through gl_FragDepth (ALWAYS: every pixel) and the albedo's sample 0.
gpu::GraphicsPipelineDesc describeDepthPipeline(const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_resolve_depth.frag", bindings);
    d.depthCompare = VK_COMPARE_OP_ALWAYS;
    return d;
}

// The per-sample mask into the stencil's reserved bit alone (REPLACE with the bit as reference,
// under the write mask the slide gives), colour and depth untouched.
gpu::GraphicsPipelineDesc describeEdgeMaskPipeline(const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_edge_mask.frag", bindings);
    d.untouchedColorAttachments = 1u;
    d.depthTest = false;
    d.depthWrite = false;
    d.stencil = {true, VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_REPLACE, kMsaaEdgeStencilBit};
    return d;
}

}  // namespace

MsaaResolve addMsaaResolvePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& multisampled) {
    MsaaResolve out{createGBufferImages(graph, scene, VK_SAMPLE_COUNT_1_BIT, "resolved"),
                    graph.createImage("resolved.maxDepth", imageDesc2D(kMaxDepthFormat, scene.width, scene.height))};
    GBuffer& resolved = out.resolved;
    const bool velocity = multisampled.velocity.valid();
    gpu::ImageHandle centreDepth =
        graph.createImage("resolved.centreDepth", imageDesc2D(kCentreDepthFormat, scene.width, scene.height));
    gpu::ImageHandle edgeQuads =
        graph.createImage("resolved.edgeQuads", imageDesc2D(kEdgeQuadsFormat, scene.width, scene.height));

    ComputePass copy{velocity ? "msaa_resolve_velocity" : "msaa_resolve",
                     {sampled(multisampled.depth), sampled(multisampled.normalRoughness),
                      sampled(multisampled.instance), bufferRead(scene.buffers.camera),
                      storageWrite(resolved.normalRoughness), storageWrite(resolved.instance),
                      storageWrite(out.maxDepth), storageWrite(centreDepth), storageWrite(edgeQuads)},
                     {}};
    if (velocity) {
        copy.bindings.push_back(sampled(multisampled.velocity));
        copy.bindings.push_back(storageWrite(resolved.velocity));
    }
    copy.label = "msaa_resolve";
    std::vector<gpu::ImageHandle> written = addComputePass(graph, std::move(copy)).images;
    resolved.normalRoughness = written[0];
    resolved.instance = written[1];
    out.maxDepth = written[2];
    centreDepth = written[3];
    edgeQuads = written[4];
    if (velocity) resolved.velocity = written[5];

    std::vector<ShaderBinding> bindings{sampled(multisampled.albedoMetallic), sampled(centreDepth),
                                        sampled(edgeQuads)};
    graph.addPass(
        "msaa_resolve_depth", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            declareBindings(pass, bindings, ShaderStage::Graphics);
            // The stencil clear happens here, so the edge bit is set again right after it (seed 000:
            // "restore whenever a stencil clear occurs"); clip volumes add their bits later.
            resolved.depth = pass.depthStencilAttachment(resolved.depth, VkClearDepthStencilValue{1.0f, 0});
            resolved.albedoMetallic =
                pass.colorAttachment(resolved.albedoMetallic, gpu::FrameGraph::PassBuilder::Load::Discard);
        },
        [bindings](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::PipelineCache& pipelines = res.pipelines();
            const gpu::Pipeline& depth = pipelines.get<gpu::GraphicsPipelineDesc>(
                "msaa_resolve_depth", [&] { return describeDepthPipeline(bindings); });
            const gpu::Pipeline& edgeMask = pipelines.get<gpu::GraphicsPipelineDesc>(
                "msaa_edge_mask", [&] { return describeEdgeMaskPipeline(bindings); });
            for (const gpu::Pipeline* pipeline : {&depth, &edgeMask}) {
                bindBindings(cmd, *pipeline, bindings, res);
                if (pipeline == &edgeMask)
                    vkCmdSetStencilWriteMask(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, kMsaaEdgeStencilBit);
                vkCmdDraw(cmd, 3, 1, 0, 0);
            }
        });
    return out;
}

}  // namespace obscura::passes
