#include "passes/tonemap.h"
#include "generated/shader_layouts.h"

#include "passes/shader_pass.h"

namespace obscura::passes {

namespace {
// Mirrors color_lut.cpp's shaper so the shader encodes exactly what the lattice was baked on.
struct TonemapPush {
    float shaperMinStops;
    float shaperRangeStops;
    float middleGrey;
    float lutSize;
    uint32_t alphaIsCoverage;
    float backdropCoverage;
};
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, shaperMinStops);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, shaperRangeStops);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, middleGrey);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, lutSize);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, alphaIsCoverage);
OBSCURA_SHADER_OFFSET(TonemapPush, tonemap_comp::Push, backdropCoverage);
}  // namespace

gpu::ImageHandle addTonemapPass(gpu::FrameGraph& graph, const FrameScene& scene, gpu::ImageHandle hdrColor,
                                HdrAlpha hdrAlpha, gpu::ImageHandle coverage, gpu::ImageHandle transparentCoverage,
                                const ColorGradingLut& grading) {
    gpu::ImageHandle display = graph.createImage("display", imageDesc2D(kDisplayFormat, scene.width, scene.height));
    gpu::ImageHandle lut = graph.importTexture("displayLut", grading.texture());
    const ColorLut& shaper = grading.lut();
    TonemapPush push{shaper.shaperMinStops, shaper.shaperMaxStops - shaper.shaperMinStops, kShaperMiddleGrey,
                     float(shaper.size), hdrAlpha == HdrAlpha::Coverage ? 1u : 0u, scene.cameraData.backdropCoverage};
    return addComputePass(graph, {"tonemap",
                                  {sampled(hdrColor), storageWrite(display), sampled(coverage),
                                   sampled(lut, SampledRead::Linear), sampled(transparentCoverage)},
                                  bytesOf(push)})
        .images[0];
}

}  // namespace obscura::passes
