#include "passes/aov_readback.h"
#include "generated/shader_layouts.h"

#include "gpu/vulkan_functions.h"
#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

// Mirrors shaders/common/display_transform.glsl: the lattice's shaper (pass_support/color_lut.h).
struct DisplayShaper {
    float minStops;
    float rangeStops;
    float middleGrey;
    float lutSize;
};
OBSCURA_SHADER_OFFSET(DisplayShaper, DisplayShaper, minStops);
OBSCURA_SHADER_OFFSET(DisplayShaper, DisplayShaper, rangeStops);
OBSCURA_SHADER_OFFSET(DisplayShaper, DisplayShaper, middleGrey);
OBSCURA_SHADER_OFFSET(DisplayShaper, DisplayShaper, lutSize);

// Mirrors the push constants of shaders/aov_pack.comp.
struct PackPush {
    uint32_t aov;
    uint32_t width;
    uint32_t height;
    uint32_t alphaIsCoverage;
    DisplayShaper shaper;
};
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, aov);
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, width);
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, height);
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, alphaIsCoverage);
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, shaper);

}  // namespace

void addAovReadbackPass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gb, gpu::ImageHandle hdrColor,
                        HdrAlpha hdrAlpha, gpu::ImageHandle transparentCoverage, const ColorGradingLut& grading,
                        gpu::ImageHandle velocity, const std::vector<AovRequest>& requests) {
    if (requests.empty()) return;
    gpu::ImageHandle lut = graph.importTexture("displayLut", grading.texture());
    const ColorLut& lattice = grading.lut();
    const DisplayShaper shaper{lattice.shaperMinStops, lattice.shaperMaxStops - lattice.shaperMinStops,
                               kShaperMiddleGrey, float(lattice.size)};
    // The pack writes one buffer per AOV, one dispatch each; where a device-local staging buffer
    // exists, a copy pass then moves it to the host-visible destination.
    std::vector<ComputePass> packs;
    std::vector<gpu::BufferHandle> destinations;
    std::vector<bool> staged;
    for (const auto& r : requests) {
        destinations.push_back(graph.importBuffer("aov", r.destination));
        staged.push_back(r.deviceStaging != nullptr);
        gpu::BufferHandle target =
            r.deviceStaging ? graph.importBuffer("aov.staging", r.deviceStaging) : destinations.back();
        PackPush push{static_cast<uint32_t>(r.aov), scene.width, scene.height,
                      hdrAlpha == HdrAlpha::Coverage ? 1u : 0u, shaper};
        ComputePass pack{"aov_pack",
                         {bufferRead(scene.buffers.camera), bufferRead(scene.buffers.instances), sampled(gb.depth),
                          sampled(gb.normalRoughness), sampled(gb.albedoMetallic), sampled(gb.instance),
                          sampled(hdrColor), sampled(lut, SampledRead::Linear), bufferWrite(target), bufferWrite(target),
                          sampled(transparentCoverage), sampled(velocity)},
                         bytesOf(push)};
        pack.texels = std::array<uint32_t, 2>{scene.width, scene.height};
        packs.push_back(std::move(pack));
    }
    std::vector<gpu::BufferHandle> packed = addComputeDispatches(graph, "aov_readback", std::move(packs)).buffers;
    std::vector<gpu::BufferHandle> copySources, copyDestinations;
    for (size_t i = 0; i < requests.size(); ++i) {
        if (staged[i]) {
            copySources.push_back(packed[i]);
            copyDestinations.push_back(destinations[i]);
        } else {
            graph.markOutput(packed[i]);
        }
    }
    if (copySources.empty()) return;
    graph.addPass(
        "aov_copy", gpu::PassKind::Transfer,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            for (size_t i = 0; i < copySources.size(); ++i) {
                pass.read(copySources[i], gpu::Usage::TransferSrc);
                graph.markOutput(pass.write(copyDestinations[i], gpu::Usage::TransferDst));
            }
        },
        [copySources, copyDestinations](VkCommandBuffer cmd, const gpu::PassResources& res) {
            for (size_t i = 0; i < copySources.size(); ++i) {
                VkBufferCopy region{0, 0, res.bufferSize(copySources[i])};
                vkCmdCopyBuffer(cmd, res.buffer(copySources[i]), res.buffer(copyDestinations[i]), 1, &region);
            }
        });
}

}  // namespace obscura::passes
