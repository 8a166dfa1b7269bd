#include "passes/bilateral_blur.h"

#include "passes/shader_pass.h"

namespace obscura::passes {

gpu::ImageHandle addBilateralBlurPass(gpu::FrameGraph& graph, const SsaoResult& ssao) {
    const gpu::ImageDesc input = graph.imageDesc(ssao.accessibility);
    gpu::ImageHandle blurred =
        graph.createImage("ssaoBlurred", imageDesc2D(kSsaoAccessibilityFormat, input.width, input.height));
    ComputePass blur{"bilateral_blur", {sampled(ssao.accessibility), sampled(ssao.halfDepth), storageWrite(blurred)}};
    blur.texelsPerGroup = {16, 32};  // bilateral_blur.comp's tile
    return addComputePass(graph, std::move(blur)).images[0];
}

}  // namespace obscura::passes
