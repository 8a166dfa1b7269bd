#include "passes/bilateral_blur.h"

#include "passes/shader_pass.h"

namespace obscura::passes {

gpu::ImageHandle addBilateralBlurPass(gpu::FrameGraph& graph, const SsaoResult& ssao) {
    const gpu::ImageDesc input = graph.imageDesc(ssao.accessibility);
    gpu::ImageHandle blurred =
        graph.createImage("ssaoBlurred", imageDesc2D(kSsaoAccessibilityFormat, input.width, input.height));
    return addComputePass(graph, {"bilateral_blur",
                                  {sampled(ssao.accessibility), sampled(ssao.halfDepth), storageWrite(blurred)}})
        .images[0];
}

}  // namespace obscura::passes
