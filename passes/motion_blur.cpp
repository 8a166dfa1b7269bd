#include "passes/motion_blur.h"

#include "generated/shader_layouts.h"
#include "passes/shader_pass.h"

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

gpu::ImageHandle addMotionBlurPasses(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gbuffer,
                                     gpu::ImageHandle hdrColor, int samples) {
    if (samples < kMinMotionBlurSamples || samples > kMaxMotionBlurSamples)
        throw std::invalid_argument("motion blur: samples out of range");
    if (!gbuffer.velocity.valid()) throw std::invalid_argument("motion blur: the G-buffer has no velocity target");
    uint32_t tilesWide = (scene.width + kTileSize - 1) / kTileSize,
             tilesHigh = (scene.height + kTileSize - 1) / kTileSize;
    MotionBlurConstants constants{motionBlurMaxRadius(scene.width, scene.height), 1.0f, samples, kSoftDepthFraction};

    gpu::ImageHandle tileMax =
        graph.createImage("motionBlurTileMax", imageDesc2D(kTileVelocityFormat, tilesWide, tilesHigh));
    gpu::ImageHandle speedDepth =
        graph.createImage("motionBlurSpeedDepth", imageDesc2D(kSpeedDepthFormat, scene.width, scene.height));
    ComputePass tiles{"motion_blur_tile_max",
                      {sampled(gbuffer.velocity), sampled(gbuffer.depth), storageWrite(tileMax),
                       storageWrite(speedDepth), bufferRead(scene.buffers.camera)},
                      bytesOf(constants)};
    tiles.texelsPerGroup = {1, 1};
    std::vector<gpu::ImageHandle> tiled = addComputePass(graph, tiles).images;
    tileMax = tiled[0];
    speedDepth = tiled[1];

    gpu::ImageHandle neighbourMax =
        graph.createImage("motionBlurNeighbourMax", imageDesc2D(kTileVelocityFormat, tilesWide, tilesHigh));
    ComputePass neighbours{"motion_blur_neighbour_max", {sampled(tileMax), storageWrite(neighbourMax)},
                           bytesOf(constants)};
    neighbours.texelsPerGroup = {1, 1};  // a workgroup per tile
    neighbourMax = addComputePass(graph, neighbours).images[0];

    // Separable [Sousa08]: the first pass covers one tap spacing of the second.
    VkFormat format = graph.imageDesc(hdrColor).format;
    auto gather = [&](gpu::ImageHandle input, const char* name, float spanScale, const char* label) {
        gpu::ImageHandle result = graph.createImage(name, imageDesc2D(format, scene.width, scene.height));
        MotionBlurConstants scaled = constants;
        scaled.spanScale = spanScale;
        ComputePass pass{"motion_blur_gather",
                         {sampled(input), sampled(speedDepth), sampled(neighbourMax), storageWrite(result)},
                         bytesOf(scaled)};
        pass.label = label;
        return addComputePass(graph, std::move(pass)).images[0];
    };
    gpu::ImageHandle prefiltered =
        gather(hdrColor, "motionBlurPrefiltered", 1.0f / float(samples), "motion_blur_gather_fine");
    return gather(prefiltered, "motionBlurColor", 1.0f, "motion_blur_gather_coarse");
}

}  // namespace obscura::passes
