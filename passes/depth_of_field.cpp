#include "passes/depth_of_field.h"

#include "generated/shader_layouts.h"
#include "passes/shader_pass.h"

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
    float pixelsPerTexel;
};
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, cocScale);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, cocBias);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, maxRadius);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, cellShare);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, rotation);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, blades);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, tapsPerSide);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, tileNeighbourhood);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, cellCentre);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, cellHalfSize);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, jitter);
OBSCURA_SHADER_OFFSET(DofConstants, DofConstants, pixelsPerTexel);

// Tile side in field texels (DOF_TILE_SIZE in dof_common.glsl): a workgroup of the downsample and
// of the gather, which reduce their tile's values in shared memory.
constexpr uint32_t kTileSize = 8;

// Fields premultiplied by their CoC, and the CoC itself (seed 000 "A plausible and
// efficient DOF reconstruction filter": R11G11B10F downscaled HDR scene, R8G8 CoC).
constexpr VkFormat kFieldInputFormat = VK_FORMAT_B10G11R11_UFLOAT_PACK32;
constexpr VkFormat kCocFormat = VK_FORMAT_R8G8_UNORM;
// The field CoC pair, and the share of each texel's pixels that belong to each field (a small bright
// point is a quarter of a half-resolution texel, not all of it).
constexpr VkFormat kFieldCocFormat = VK_FORMAT_R8G8B8A8_UNORM;
// The gathered fields carry their coverage in alpha, which R11G11B10F has no room for.
constexpr VkFormat kFieldFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

// One pass of the chain, one invocation per texel of its first output, `texelsPerGroup` of them a
// workgroup; returns what it wrote.
std::vector<gpu::ImageHandle> addDofPass(gpu::FrameGraph& graph, const std::string& name,
                                         std::vector<ShaderBinding> bindings, const DofConstants& constants,
                                         uint32_t texelsPerGroup) {
    ComputePass pass{name, std::move(bindings), bytesOf(constants)};
    pass.texelsPerGroup = {texelsPerGroup, texelsPerGroup};
    return addComputePass(graph, std::move(pass)).images;
}

}  // namespace

double maxDofRadiusPixels(int tapsPerSide) { return 4.0 * tapsPerSide; }

gpu::ImageHandle addDepthOfFieldPasses(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gbuffer,
                                       gpu::ImageHandle hdrColor, const DepthOfFieldSettings& settings) {
    if (settings.tapsPerSide < kMinDofTapsPerSide || settings.tapsPerSide > kMaxDofTapsPerSide)
        throw std::invalid_argument("depth of field: taps per side out of range");
    const ApertureCell& cell = settings.cell;
    double maxRadius = maxDofRadiusPixels(settings.tapsPerSide) / cell.share();
    // A near CoC reaches as far as the cell does from its centre's point, at most.
    double reach = maxRadius * apertureCellReach(cell, settings.aperture);
    const uint32_t pixelsPerTexel = settings.resolution == FieldResolution::Half ? 2 : 1;
    DofConstants constants{float(settings.coc.scale),
                           float(settings.coc.bias),
                           float(maxRadius),
                           float(cell.share()),
                           float(settings.aperture.rotation),
                           settings.aperture.blades,
                           settings.tapsPerSide,
                           int32_t(std::ceil(reach / pixelsPerTexel / kTileSize)),
                           {float(cell.centre[0]), float(cell.centre[1])},
                           {float(cell.halfSize[0]), float(cell.halfSize[1])},
                           {float(settings.jitter[0]), float(settings.jitter[1])},
                           float(pixelsPerTexel)};

    uint32_t fieldWidth = (scene.width + pixelsPerTexel - 1) / pixelsPerTexel;
    uint32_t fieldHeight = (scene.height + pixelsPerTexel - 1) / pixelsPerTexel;
    uint32_t tilesWide = (fieldWidth + kTileSize - 1) / kTileSize, tilesHigh = (fieldHeight + kTileSize - 1) / kTileSize;
    auto field = [&](const char* name, VkFormat format) {
        return graph.createImage(name, imageDesc2D(format, fieldWidth, fieldHeight));
    };
    auto tiles = [&](const char* name) {
        return graph.createImage(name, imageDesc2D(kCocFormat, tilesWide, tilesHigh));
    };
    const SampledRead linear = SampledRead::Linear;

    // Frames an integral is made of come in RGBA16F (docs/ARCHITECTURE.md "Accumulation
    // precision"); their layers keep it, or the small float format's truncation would bias the mean.
    const VkFormat hdrFormat = graph.imageDesc(hdrColor).format;
    const VkFormat layerFormat = hdrFormat == kFieldFormat ? kFieldFormat : kFieldInputFormat;
    // A workgroup a tile: each writes its tile's CoC as well.
    std::vector<gpu::ImageHandle> layers = addDofPass(
        graph, "dof_downsample",
        {sampled(hdrColor), sampled(gbuffer.depth), storageWrite(field("dofNearLayer", layerFormat)),
         storageWrite(field("dofFarLayer", layerFormat)), storageWrite(field("dofFieldCoc", kFieldCocFormat)),
         storageWrite(tiles("dofTileCoc"))},
        constants, kTileSize);
    const gpu::ImageHandle nearLayer = layers[0], farLayer = layers[1], fieldCoc = layers[2], tileCoc = layers[3];

    // A workgroup a tile: each finds its tile's neighbourhood first and writes it for the composite.
    std::vector<gpu::ImageHandle> gathered = addDofPass(
        graph, "dof_gather",
        {sampled(nearLayer, linear), sampled(farLayer, linear), sampled(fieldCoc, linear), sampled(tileCoc),
         storageWrite(field("dofNearGathered", kFieldFormat)), storageWrite(field("dofFarGathered", kFieldFormat)),
         storageWrite(tiles("dofTileNeighbourhood"))},
        constants, kTileSize);
    const gpu::ImageHandle neighbourhood = gathered[2];

    std::vector<gpu::ImageHandle> fields = addDofPass(
        graph, "dof_flood_fill",
        {sampled(gathered[0], linear), sampled(gathered[1], linear), sampled(fieldCoc), sampled(neighbourhood),
         storageWrite(field("dofNearField", kFieldFormat)), storageWrite(field("dofFarField", kFieldFormat))},
        constants, 8);

    gpu::ImageHandle output = graph.createImage("dofColor", imageDesc2D(hdrFormat, scene.width, scene.height));
    return addDofPass(graph, "dof_composite",
                      {sampled(hdrColor), sampled(gbuffer.depth), sampled(fields[0], linear),
                       sampled(fields[1], linear), sampled(fieldCoc, linear), sampled(neighbourhood),
                       storageWrite(output)},
                      constants, 8)[0];
}

}  // namespace obscura::passes
