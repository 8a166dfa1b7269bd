#include "passes/edge_aa.h"

#include "passes/image_compute_pass.h"

namespace obscura::passes {
namespace {

constexpr VkFormat kEdgesFormat = VK_FORMAT_R8G8_UNORM;
// Areas are at most 1/2: 8 bits hold them to 1/510 (SMAA keeps its weights in RGBA8 too).
constexpr VkFormat kWeightsFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kBlendedFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

}  // namespace

gpu::ImageHandle addEdgeAaPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                 const GBuffer& gbuffer, gpu::ImageHandle hdrColor) {
    gpu::ImageHandle edges = graph.createImage("edgeAaEdges", chainImage(kEdgesFormat, scene.width, scene.height));
    ImageComputePass detect{"edge_aa_edges",
                            {{hdrColor, SampledRead::Nearest},
                             {gbuffer.instance, SampledRead::Nearest},
                             {gbuffer.depth, SampledRead::Depth},
                             {gbuffer.normalRoughness, SampledRead::Nearest}},
                            {edges},
                            {}};
    detect.camera = scene.camera->buffer;
    detect.storageBuffers = {scene.instances->buffer};
    addImageComputePass(graph, pipelines, detect);

    gpu::ImageHandle weights =
        graph.createImage("edgeAaWeights", chainImage(kWeightsFormat, scene.width, scene.height));
    addImageComputePass(graph, pipelines, {"edge_aa_weights", {{edges, SampledRead::Nearest}}, {weights}, {}});

    gpu::ImageHandle blended =
        graph.createImage("edgeAaColor", chainImage(kBlendedFormat, scene.width, scene.height));
    addImageComputePass(graph, pipelines,
                        {"edge_aa_blend", {{hdrColor, SampledRead::Nearest}, {weights, SampledRead::Nearest}}, {blended}, {}});
    return blended;
}

}  // namespace obscura::passes
