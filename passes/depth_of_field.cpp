#include "passes/depth_of_field.h"

#include "passes/image_compute_pass.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace obscura::passes {
namespace {

// Mirrors the push constants of shaders/common/dof_common.glsl; every DOF pass gets all of them.
struct DofConstants {
    float cocScale;
    float cocBias;
    float maxRadius;
    float cellShare;
    float rotation;
    int32_t blades;
    int32_t tapsPerSide;
    int32_t tileNeighbourhood;
    std::array<float, 2> cellCentre;
    std::array<float, 2> cellHalfSize;
    std::array<float, 2> jitter;
};

// Tile side in half-resolution texels (DOF_TILE_SIZE in dof_common.glsl).
constexpr uint32_t kTileSize = 8;

// Half-resolution fields premultiplied by their CoC, and the CoC itself (seed 000 "A plausible and
// efficient DOF reconstruction filter": R11G11B10F downscaled HDR scene, R8G8 CoC).
constexpr VkFormat kFieldInputFormat = VK_FORMAT_B10G11R11_UFLOAT_PACK32;
constexpr VkFormat kCocFormat = VK_FORMAT_R8G8_UNORM;
// The half-resolution CoC pair, and the share of each texel's four pixels that belong to each field
// (a small bright point is a quarter of its texel, not all of it).
constexpr VkFormat kHalfCocFormat = VK_FORMAT_R8G8B8A8_UNORM;
// The gathered fields carry their coverage in alpha, which R11G11B10F has no room for.
constexpr VkFormat kFieldFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

// One pass of the chain, one invocation per texel of its first output.
void addDofPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const std::string& name,
                std::vector<SampledInput> inputs, std::vector<gpu::ImageHandle> outputs, const DofConstants& constants) {
    addImageComputePass(graph, pipelines, {name, std::move(inputs), std::move(outputs), pushConstantBytes(constants)});
}

}  // namespace

double maxDofRadiusPixels(int tapsPerSide) { return 4.0 * tapsPerSide; }

gpu::ImageHandle addDepthOfFieldPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                       const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                       const DepthOfFieldSettings& settings) {
    if (settings.tapsPerSide < kMinDofTapsPerSide || settings.tapsPerSide > kMaxDofTapsPerSide)
        throw std::invalid_argument("depth of field: taps per side out of range");
    const ApertureCell& cell = settings.cell;
    double maxRadius = maxDofRadiusPixels(settings.tapsPerSide) / cell.share();
    // A near CoC reaches as far as the cell does from its centre's point, at most.
    double reach = maxRadius * apertureCellReach(cell, settings.aperture);
    DofConstants constants{float(settings.coc.scale),
                           float(settings.coc.bias),
                           float(maxRadius),
                           float(cell.share()),
                           float(settings.aperture.rotation),
                           settings.aperture.blades,
                           settings.tapsPerSide,
                           int32_t(std::ceil(0.5 * reach / kTileSize)),
                           {float(cell.centre[0]), float(cell.centre[1])},
                           {float(cell.halfSize[0]), float(cell.halfSize[1])},
                           {float(settings.jitter[0]), float(settings.jitter[1])}};

    uint32_t halfWidth = (scene.width + 1) / 2, halfHeight = (scene.height + 1) / 2;
    uint32_t tilesWide = (halfWidth + kTileSize - 1) / kTileSize, tilesHigh = (halfHeight + kTileSize - 1) / kTileSize;
    gpu::ImageHandle nearLayer = graph.createImage("dofNearLayer", chainImage(kFieldInputFormat, halfWidth, halfHeight));
    gpu::ImageHandle farLayer = graph.createImage("dofFarLayer", chainImage(kFieldInputFormat, halfWidth, halfHeight));
    gpu::ImageHandle halfCoc = graph.createImage("dofHalfCoc", chainImage(kHalfCocFormat, halfWidth, halfHeight));
    addDofPass(graph, pipelines, "dof_downsample", {{hdrColor, SampledRead::Nearest}, {gbuffer.depth, SampledRead::Depth}},
               {nearLayer, farLayer, halfCoc}, constants);

    gpu::ImageHandle tiles = graph.createImage("dofTileCoc", chainImage(kCocFormat, tilesWide, tilesHigh));
    addDofPass(graph, pipelines, "dof_tile_min_max", {{halfCoc, SampledRead::Nearest}}, {tiles}, constants);
    gpu::ImageHandle neighbourhood = graph.createImage("dofTileNeighbourhood", chainImage(kCocFormat, tilesWide, tilesHigh));
    addDofPass(graph, pipelines, "dof_tile_neighbourhood", {{tiles, SampledRead::Nearest}}, {neighbourhood}, constants);

    gpu::ImageHandle nearGathered = graph.createImage("dofNearGathered", chainImage(kFieldFormat, halfWidth, halfHeight));
    gpu::ImageHandle farGathered = graph.createImage("dofFarGathered", chainImage(kFieldFormat, halfWidth, halfHeight));
    addDofPass(graph, pipelines, "dof_gather",
               {{nearLayer, SampledRead::Linear}, {farLayer, SampledRead::Linear}, {halfCoc, SampledRead::Linear}, {neighbourhood, SampledRead::Nearest}},
               {nearGathered, farGathered}, constants);

    gpu::ImageHandle nearField = graph.createImage("dofNearField", chainImage(kFieldFormat, halfWidth, halfHeight));
    gpu::ImageHandle farField = graph.createImage("dofFarField", chainImage(kFieldFormat, halfWidth, halfHeight));
    addDofPass(graph, pipelines, "dof_flood_fill",
               {{nearGathered, SampledRead::Linear}, {farGathered, SampledRead::Linear}, {halfCoc, SampledRead::Nearest},
                {neighbourhood, SampledRead::Nearest}},
               {nearField, farField}, constants);

    gpu::ImageHandle output = graph.createImage("dofColor", chainImage(graph.imageDesc(hdrColor).format, scene.width, scene.height));
    addDofPass(graph, pipelines, "dof_composite",
               {{hdrColor, SampledRead::Nearest}, {gbuffer.depth, SampledRead::Depth}, {nearField, SampledRead::Linear},
                {farField, SampledRead::Linear}, {halfCoc, SampledRead::Linear}, {neighbourhood, SampledRead::Nearest}},
               {output}, constants);
    return output;
}

}  // namespace obscura::passes
