#include "passes/accumulate.h"
#include "generated/shader_layouts.h"

#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

// Mirrors the push constants of shaders/accumulate.comp.
struct AccumulatePush {
    float weight;
    uint32_t first;
    uint32_t guardPixels;
};
OBSCURA_SHADER_OFFSET(AccumulatePush, accumulate_comp::Push, weight);
OBSCURA_SHADER_OFFSET(AccumulatePush, accumulate_comp::Push, first);
OBSCURA_SHADER_OFFSET(AccumulatePush, accumulate_comp::Push, guardPixels);

}  // namespace

void addAccumulatePass(gpu::FrameGraph& graph, gpu::ImageHandle hdrColor, gpu::ImageHandle accumulation, float weight,
                       bool first, uint32_t guardPixels) {
    AccumulatePush push{weight, first ? 1u : 0u, guardPixels};
    // The first sub-frame overwrites what the sum held.
    addComputePass(graph, {"accumulate",
                           {sampled(hdrColor), first ? storageWrite(accumulation) : storageReadWrite(accumulation)},
                           bytesOf(push)});
}

gpu::ImageHandle addAccumulationResolvePass(gpu::FrameGraph& graph, gpu::ImageHandle accumulation, VkFormat format) {
    const gpu::ImageDesc sum = graph.imageDesc(accumulation);
    gpu::ImageHandle resolved = graph.createImage("accumulationResolved", imageDesc2D(format, sum.width, sum.height));
    return addComputePass(graph, {"accumulate_resolve", {storageRead(accumulation), storageWrite(resolved)}}).images[0];
}

}  // namespace obscura::passes
