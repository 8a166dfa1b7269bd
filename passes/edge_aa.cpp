#include "passes/edge_aa.h"

#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

constexpr VkFormat kEdgesFormat = VK_FORMAT_R8G8_UNORM;
// Areas are at most 1/2: 8 bits hold them to 1/510 (SMAA keeps its weights in RGBA8 too).
constexpr VkFormat kWeightsFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kBlendedFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

}  // namespace

gpu::ImageHandle addEdgeAaPasses(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gbuffer,
                                 gpu::ImageHandle hdrColor) {
    gpu::ImageHandle edges = graph.createImage("edgeAaEdges", imageDesc2D(kEdgesFormat, scene.width, scene.height));
    edges = addComputePass(graph, {"edge_aa_edges",
                                   {sampled(hdrColor), sampled(gbuffer.instance), sampled(gbuffer.depth),
                                    sampled(gbuffer.normalRoughness), storageWrite(edges),
                                    bufferRead(scene.buffers.camera), bufferRead(scene.buffers.instances)}})
                .images[0];

    gpu::ImageHandle weights =
        graph.createImage("edgeAaWeights", imageDesc2D(kWeightsFormat, scene.width, scene.height));
    weights = addComputePass(graph, {"edge_aa_weights", {sampled(edges), storageWrite(weights)}}).images[0];

    gpu::ImageHandle blended =
        graph.createImage("edgeAaColor", imageDesc2D(kBlendedFormat, scene.width, scene.height));
    return addComputePass(graph, {"edge_aa_blend", {sampled(hdrColor), sampled(weights), storageWrite(blended)}})
        .images[0];
}

}  // namespace obscura::passes
