#include "passes/msaa_resolve.h"

#include "gpu/vulkan_functions.h"
#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

// The depth msaa_resolve.comp chose per pixel: the resolved G-buffer's depth, unless clip volumes
// need it in a depth/stencil attachment.
constexpr VkFormat kCentreDepthFormat = VK_FORMAT_R32_SFLOAT;
// The stencil value each pixel starts the lighting with: kMsaaEdgeStencilBit where the pixel's 2x2
// quad holds a pixel whose samples differ, else 0.
constexpr VkFormat kEdgeStencilFormat = VK_FORMAT_R8_UINT;

// Both draws of the raster half, which only clip volumes need: the depth target, then the tagged
// quads' stencil bit.
gpu::GraphicsPipelineDesc describeFullScreenPass(const char* fragmentShader, const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d;
    d.vertexShader = "fullscreen_triangle.vert";
    d.fragmentShader = fragmentShader;
    d.bindings = bindingLayout(bindings);
    d.depthFormat = kDepthFormat;
    return d;
}

// The chosen depth through gl_FragDepth (ALWAYS: every pixel).
gpu::GraphicsPipelineDesc describeDepthPipeline(const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_resolve_depth.frag", bindings);
    d.depthCompare = VK_COMPARE_OP_ALWAYS;
    return d;
}

// The per-sample mask into the stencil's reserved bit alone (REPLACE with the bit as reference,
// under the write mask the slide gives), depth untouched.
gpu::GraphicsPipelineDesc describeEdgeMaskPipeline(const std::vector<ShaderBinding>& bindings) {
    gpu::GraphicsPipelineDesc d = describeFullScreenPass("msaa_edge_mask.frag", bindings);
    d.depthTest = false;
    d.depthWrite = false;
    d.stencil = {true, VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_REPLACE, kMsaaEdgeStencilBit};
    return d;
}

// The depth/stencil target the clip volumes test and mark: the chosen depths, the stencil cleared
// with the edge bit set again right after (seed 000: "restore whenever a stencil clear occurs").
gpu::ImageHandle addDepthStencilPass(gpu::FrameGraph& graph, const FrameScene& scene, gpu::ImageHandle centreDepth,
                                     gpu::ImageHandle edgeStencil) {
    gpu::ImageHandle depthStencil =
        graph.createImage("resolved.depth", imageDesc2D(kDepthFormat, scene.width, scene.height));
    std::vector<ShaderBinding> bindings{sampled(centreDepth), sampled(edgeStencil)};
    const gpu::PipelineCache::Request depthPipeline = gpu::PipelineCache::request<gpu::GraphicsPipelineDesc>(
        "msaa_resolve_depth", [bindings] { return describeDepthPipeline(bindings); });
    const gpu::PipelineCache::Request edgeMaskPipeline = gpu::PipelineCache::request<gpu::GraphicsPipelineDesc>(
        "msaa_edge_mask", [bindings] { return describeEdgeMaskPipeline(bindings); });
    graph.addPass(
        "msaa_resolve_depth", gpu::PassKind::Raster,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.usesPipeline(depthPipeline);
            pass.usesPipeline(edgeMaskPipeline);
            declareBindings(pass, bindings, ShaderStage::Graphics);
            depthStencil = pass.depthStencilAttachment(depthStencil, VkClearDepthStencilValue{1.0f, 0});
        },
        [bindings, depthPipeline, edgeMaskPipeline](VkCommandBuffer cmd, const gpu::PassResources& res) {
            const gpu::Pipeline& depth = res.pipelines().get(depthPipeline);
            const gpu::Pipeline& edgeMask = res.pipelines().get(edgeMaskPipeline);
            for (const gpu::Pipeline* pipeline : {&depth, &edgeMask}) {
                bindBindings(cmd, *pipeline, bindings, res);
                if (pipeline == &edgeMask)
                    vkCmdSetStencilWriteMask(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, kMsaaEdgeStencilBit);
                vkCmdDraw(cmd, 3, 1, 0, 0);
            }
        });
    return depthStencil;
}

}  // namespace

MsaaResolve addMsaaResolvePass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& multisampled) {
    auto image = [&](const char* name, VkFormat format) {
        return graph.createImage(std::string("resolved.") + name, imageDesc2D(format, scene.width, scene.height));
    };
    MsaaResolve out{{image("centreDepth", kCentreDepthFormat), image("normalRoughness", kNormalRoughnessFormat),
                     image("albedoMetallic", kAlbedoMetallicFormat), image("instance", kInstanceFormat), {},
                     image("edgeStencil", kEdgeStencilFormat)},
                    image("maxDepth", kMaxDepthFormat)};
    GBuffer& resolved = out.resolved;
    const bool velocity = multisampled.velocity.valid();

    ComputePass resolve{velocity ? "msaa_resolve_velocity" : "msaa_resolve",
                        {sampled(multisampled.depth), sampled(multisampled.normalRoughness),
                         sampled(multisampled.albedoMetallic), sampled(multisampled.instance),
                         bufferRead(scene.buffers.camera), storageWrite(resolved.normalRoughness),
                         storageWrite(resolved.albedoMetallic), storageWrite(resolved.instance),
                         storageWrite(out.maxDepth), storageWrite(resolved.depth), storageWrite(resolved.stencil)},
                        {}};
    if (velocity) {
        resolved.velocity = image("velocity", kVelocityFormat);
        resolve.bindings.push_back(sampled(multisampled.velocity));
        resolve.bindings.push_back(storageWrite(resolved.velocity));
    }
    resolve.label = "msaa_resolve";
    std::vector<gpu::ImageHandle> written = addComputePass(graph, std::move(resolve)).images;
    resolved.normalRoughness = written[0];
    resolved.albedoMetallic = written[1];
    resolved.instance = written[2];
    out.maxDepth = written[3];
    resolved.depth = written[4];
    resolved.stencil = written[5];
    if (velocity) resolved.velocity = written[6];

    // Clip volumes rasterise against the depth and keep their bits beside the edge bit in a
    // stencil: only then are the depth and the mask copied into a depth/stencil target.
    if (!scene.clipVolumes.empty()) {
        resolved.depth = addDepthStencilPass(graph, scene, resolved.depth, resolved.stencil);
        resolved.stencil = {};
    }
    return out;
}

}  // namespace obscura::passes
