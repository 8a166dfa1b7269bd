#include "passes/depth_of_field.h"

#include <cmath>
#include <stdexcept>

namespace obscura::passes {
namespace {

// Mirrors the push constants of shaders/common/dof_common.glsl; every DOF pass gets all of them.
struct DofConstants {
    float cocScale;
    float cocBias;
    float maxRadius;
    float polygonBlend;
    float rotation;
    int32_t blades;
    int32_t tapsPerSide;
    int32_t tileNeighbourhood;
};

// Tile side in half-resolution texels (DOF_TILE_SIZE in dof_common.glsl).
constexpr uint32_t kTileSize = 8;

// Half-resolution fields premultiplied by their CoC, and the CoC itself (seed 000 "A plausible and
// efficient DOF reconstruction filter": R11G11B10F downscaled HDR scene, R8G8 CoC).
constexpr VkFormat kFieldInputFormat = VK_FORMAT_B10G11R11_UFLOAT_PACK32;
constexpr VkFormat kCocFormat = VK_FORMAT_R8G8_UNORM;
// The gathered fields carry their coverage in alpha, which R11G11B10F has no room for.
constexpr VkFormat kFieldFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

enum class Read { Nearest, Linear, Depth };

struct Input {
    gpu::ImageHandle image;
    Read read;
};

// One compute pass of the chain: inputs bound as sampled images (bindings 0..n-1), outputs as
// storage images after them, one invocation per texel of the first output.
void addDofPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const std::string& name,
                const std::vector<Input>& inputs, const std::vector<gpu::ImageHandle>& outputs,
                const DofConstants& constants) {
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>(name, [&] {
        gpu::ComputePipelineDesc desc{name + ".comp", {}, sizeof(DofConstants)};
        uint32_t binding = 0;
        for (size_t i = 0; i < inputs.size(); ++i)
            desc.bindings.push_back({binding++, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
        for (size_t i = 0; i < outputs.size(); ++i) desc.bindings.push_back({binding++, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
        return desc;
    });
    gpu::Device& device = pipelines.device();
    graph.addPass(
        name, gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            for (const Input& input : inputs) pass.read(input.image, gpu::Usage::SampledCompute);
            for (gpu::ImageHandle output : outputs) pass.write(output, gpu::Usage::StorageImageWrite);
        },
        [&device, &pipeline, inputs, outputs, constants](VkCommandBuffer cmd, const gpu::PassResources& res) {
            gpu::DescriptorWriter writer(device, pipeline);
            uint32_t binding = 0;
            for (const Input& input : inputs) {
                VkSampler sampler = input.read == Read::Linear ? device.linearClampSampler() : device.nearestClampSampler();
                writer.sampled(binding++, res.view(input.image), sampler,
                               input.read == Read::Depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                                         : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
            }
            for (gpu::ImageHandle output : outputs) writer.storageImage(binding++, res.view(output));
            writer.bind(cmd);
            vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
            const gpu::ImageDesc& size = res.desc(outputs.front());
            gpu::dispatch2D(cmd, size.width, size.height);
        });
}

gpu::ImageDesc imageOf(VkFormat format, uint32_t width, uint32_t height) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = width;
    desc.height = height;
    return desc;
}

}  // namespace

double maxDofRadiusPixels(int tapsPerSide) { return 4.0 * tapsPerSide; }

gpu::ImageHandle addDepthOfFieldPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                                       const GBuffer& gbuffer, gpu::ImageHandle hdrColor,
                                       const DepthOfFieldSettings& settings) {
    if (settings.tapsPerSide < kMinDofTapsPerSide || settings.tapsPerSide > kMaxDofTapsPerSide)
        throw std::invalid_argument("depth of field: taps per side out of range");
    double maxRadius = maxDofRadiusPixels(settings.tapsPerSide);
    DofConstants constants{float(settings.coc.scale),
                           float(settings.coc.bias),
                           float(maxRadius),
                           float(settings.aperture.polygonBlend),
                           float(settings.aperture.rotation),
                           settings.aperture.blades,
                           settings.tapsPerSide,
                           int32_t(std::ceil(0.5 * maxRadius / kTileSize))};

    uint32_t halfWidth = (scene.width + 1) / 2, halfHeight = (scene.height + 1) / 2;
    uint32_t tilesWide = (halfWidth + kTileSize - 1) / kTileSize, tilesHigh = (halfHeight + kTileSize - 1) / kTileSize;
    gpu::ImageHandle nearLayer = graph.createImage("dofNearLayer", imageOf(kFieldInputFormat, halfWidth, halfHeight));
    gpu::ImageHandle farLayer = graph.createImage("dofFarLayer", imageOf(kFieldInputFormat, halfWidth, halfHeight));
    gpu::ImageHandle halfCoc = graph.createImage("dofHalfCoc", imageOf(kCocFormat, halfWidth, halfHeight));
    addDofPass(graph, pipelines, "dof_downsample", {{hdrColor, Read::Nearest}, {gbuffer.depth, Read::Depth}},
               {nearLayer, farLayer, halfCoc}, constants);

    gpu::ImageHandle tiles = graph.createImage("dofTileCoc", imageOf(kCocFormat, tilesWide, tilesHigh));
    addDofPass(graph, pipelines, "dof_tile_min_max", {{halfCoc, Read::Nearest}}, {tiles}, constants);
    gpu::ImageHandle neighbourhood = graph.createImage("dofTileNeighbourhood", imageOf(kCocFormat, tilesWide, tilesHigh));
    addDofPass(graph, pipelines, "dof_tile_neighbourhood", {{tiles, Read::Nearest}}, {neighbourhood}, constants);

    gpu::ImageHandle nearGathered = graph.createImage("dofNearGathered", imageOf(kFieldFormat, halfWidth, halfHeight));
    gpu::ImageHandle farGathered = graph.createImage("dofFarGathered", imageOf(kFieldFormat, halfWidth, halfHeight));
    addDofPass(graph, pipelines, "dof_gather",
               {{nearLayer, Read::Linear}, {farLayer, Read::Linear}, {halfCoc, Read::Linear}, {neighbourhood, Read::Nearest}},
               {nearGathered, farGathered}, constants);

    gpu::ImageHandle nearField = graph.createImage("dofNearField", imageOf(kFieldFormat, halfWidth, halfHeight));
    gpu::ImageHandle farField = graph.createImage("dofFarField", imageOf(kFieldFormat, halfWidth, halfHeight));
    addDofPass(graph, pipelines, "dof_flood_fill",
               {{nearGathered, Read::Linear}, {farGathered, Read::Linear}, {halfCoc, Read::Nearest},
                {neighbourhood, Read::Nearest}},
               {nearField, farField}, constants);

    gpu::ImageHandle output = graph.createImage("dofColor", imageOf(graph.imageDesc(hdrColor).format, scene.width, scene.height));
    addDofPass(graph, pipelines, "dof_composite",
               {{hdrColor, Read::Nearest}, {gbuffer.depth, Read::Depth}, {nearField, Read::Linear},
                {farField, Read::Linear}, {halfCoc, Read::Linear}, {neighbourhood, Read::Nearest}},
               {output}, constants);
    return output;
}

}  // namespace obscura::passes
