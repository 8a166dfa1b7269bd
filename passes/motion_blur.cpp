#include "passes/motion_blur.h"

#include "generated/shader_layouts.h"
#include "passes/image_compute_pass.h"

#include <algorithm>
#include <stdexcept>

namespace obscura::passes {
namespace {

// Mirrors shaders/common/motion_blur_common.glsl.
struct MotionBlurConstants {
    float maxRadius;
    float spanScale;
    int32_t samples;
    float softDepth;
};
OBSCURA_SHADER_OFFSET(MotionBlurConstants, MotionBlurConstants, maxRadius);
OBSCURA_SHADER_OFFSET(MotionBlurConstants, MotionBlurConstants, spanScale);
OBSCURA_SHADER_OFFSET(MotionBlurConstants, MotionBlurConstants, samples);
OBSCURA_SHADER_OFFSET(MotionBlurConstants, MotionBlurConstants, softDepth);

constexpr uint32_t kTileSize = 32;  // MOTION_BLUR_TILE_SIZE
static_assert(float(kTileSize) == kMotionBlurTileSize);
// Soft depth comparison over 1% of the centre's depth: surfaces that close blur together
// (McGuire 2012's SOFT_Z_EXTENT, made relative so it does not depend on the scene's units).
constexpr float kSoftDepthFraction = 0.01f;
// |V| and linear depth per pixel; the tiles' velocities.
constexpr VkFormat kSpeedDepthFormat = VK_FORMAT_R16G16_SFLOAT;
constexpr VkFormat kTileVelocityFormat = VK_FORMAT_R16G16_SFLOAT;

}  // namespace

float motionBlurMaxRadius(uint32_t width, uint32_t height) {
    return std::max(kMotionBlurTileSize, 0.25f * float(std::max(width, height)));
}

gpu::ImageHandle addMotionBlurPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                     const GBuffer& gbuffer, gpu::ImageHandle hdrColor, int samples) {
    if (samples < kMinMotionBlurSamples || samples > kMaxMotionBlurSamples)
        throw std::invalid_argument("motion blur: samples out of range");
    if (!gbuffer.velocity.valid()) throw std::invalid_argument("motion blur: the G-buffer has no velocity target");
    uint32_t tilesWide = (scene.width + kTileSize - 1) / kTileSize, tilesHigh = (scene.height + kTileSize - 1) / kTileSize;
    MotionBlurConstants constants{motionBlurMaxRadius(scene.width, scene.height), 1.0f, samples, kSoftDepthFraction};

    gpu::ImageHandle tileMax = graph.createImage("motionBlurTileMax", chainImage(kTileVelocityFormat, tilesWide, tilesHigh));
    gpu::ImageHandle speedDepth =
        graph.createImage("motionBlurSpeedDepth", chainImage(kSpeedDepthFormat, scene.width, scene.height));
    ImageComputePass tiles{"motion_blur_tile_max",
                           {{gbuffer.velocity, SampledRead::Nearest}, {gbuffer.depth, SampledRead::Depth}},
                           {tileMax, speedDepth},
                           pushConstantBytes(constants)};
    tiles.camera = scene.camera->buffer;
    tiles.texelsPerGroup = 1;
    addImageComputePass(graph, pipelines, tiles);

    gpu::ImageHandle neighbourMax =
        graph.createImage("motionBlurNeighbourMax", chainImage(kTileVelocityFormat, tilesWide, tilesHigh));
    addImageComputePass(graph, pipelines,
                        {"motion_blur_neighbour_max", {{tileMax, SampledRead::Nearest}}, {neighbourMax},
                         pushConstantBytes(constants)});

    // Separable [Sousa08]: the first pass covers one tap spacing of the second.
    VkFormat format = graph.imageDesc(hdrColor).format;
    auto gather = [&](gpu::ImageHandle input, const char* name, float spanScale, const char* label) {
        gpu::ImageHandle result = graph.createImage(name, chainImage(format, scene.width, scene.height));
        MotionBlurConstants pass = constants;
        pass.spanScale = spanScale;
        ImageComputePass desc{"motion_blur_gather",
                              {{input, SampledRead::Nearest},
                               {speedDepth, SampledRead::Nearest},
                               {neighbourMax, SampledRead::Nearest}},
                              {result},
                              pushConstantBytes(pass)};
        desc.label = label;
        addImageComputePass(graph, pipelines, desc);
        return result;
    };
    gpu::ImageHandle prefiltered =
        gather(hdrColor, "motionBlurPrefiltered", 1.0f / float(samples), "motion_blur_gather_fine");
    gpu::ImageHandle output = gather(prefiltered, "motionBlurColor", 1.0f, "motion_blur_gather_coarse");
    return output;
}

}  // namespace obscura::passes
