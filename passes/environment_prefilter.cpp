#include "passes/environment_prefilter.h"

#include "generated/shader_layouts.h"
#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::passes {
namespace {

// Mirrors the push constants of shaders/environment_prefilter.comp.
struct PrefilterPush {
    float roughness;
    float mirrorLod;
    float sourceTexelSolidAngle;
    float sourceLastLod;
};
OBSCURA_SHADER_OFFSET(PrefilterPush, environment_prefilter_comp::Push, roughness);
OBSCURA_SHADER_OFFSET(PrefilterPush, environment_prefilter_comp::Push, mirrorLod);
OBSCURA_SHADER_OFFSET(PrefilterPush, environment_prefilter_comp::Push, sourceTexelSolidAngle);
OBSCURA_SHADER_OFFSET(PrefilterPush, environment_prefilter_comp::Push, sourceLastLod);

// Mirrors the push constants of shaders/environment_irradiance.comp.
struct IrradiancePush {
    int32_t level;
};
OBSCURA_SHADER_OFFSET(IrradiancePush, environment_irradiance_comp::Push, level);

// The irradiance projection reads the first source mip at most this wide: bands 0..2 need far
// fewer texels, and box-filtered mips keep the mean radiance.
constexpr uint32_t kIrradianceSourceWidth = 256;

}  // namespace

void addEnvironmentPrefilterPasses(gpu::FrameGraph& graph, PipelineCache& pipelines, gpu::ImageHandle source,
                                   const EnvironmentLighting& target) {
    gpu::Device& device = pipelines.device();
    const gpu::Pipeline& prefilter = pipelines.get<gpu::ComputePipelineDesc>("environment_prefilter", [] {
        return gpu::ComputePipelineDesc{"environment_prefilter.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                        sizeof(PrefilterPush)};
    });
    const gpu::ImageDesc& sourceDesc = graph.imageDesc(source);
    const double sourceLevels = double(sourceDesc.mipLevels);
    const PrefilterPush common{
        0.0f,
        float(std::clamp(std::log2(double(sourceDesc.width) / double(kPrefilteredWidth)), 0.0, sourceLevels - 1.0)),
        float(4.0 * std::numbers::pi / (double(sourceDesc.width) * double(sourceDesc.height))),
        float(sourceLevels - 1.0)};
    graph.addPass(
        kEnvironmentPrefilterPass, gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(source, gpu::Usage::SampledCompute);
            pass.write(target.prefiltered, gpu::Usage::StorageImageWrite);
        },
        [&device, &prefilter, source, target, common](VkCommandBuffer cmd, const gpu::PassResources& res) {
            // Levels are independent (each reads only the source): no barrier between dispatches.
            for (uint32_t level = 0; level < kPrefilteredLevels; ++level) {
                gpu::DescriptorWriter(device, prefilter)
                    .sampled(0, res.view(source), target.sampler)
                    .storageImage(1, res.levelView(target.prefiltered, level))
                    .bind(cmd);
                PrefilterPush push = common;
                push.roughness = float(level) / float(kPrefilteredLevels - 1);
                vkCmdPushConstants(cmd, prefilter.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
                const gpu::ImageDesc& size = res.desc(target.prefiltered);
                gpu::dispatch2D(cmd, std::max(size.width >> level, 1u), std::max(size.height >> level, 1u));
            }
        });

    const gpu::Pipeline& irradiance = pipelines.get<gpu::ComputePipelineDesc>("environment_irradiance", [] {
        return gpu::ComputePipelineDesc{"environment_irradiance.comp",
                                        {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                                        sizeof(IrradiancePush)};
    });
    IrradiancePush irradiancePush{0};
    while (uint32_t(irradiancePush.level) + 1 < sourceDesc.mipLevels &&
           (sourceDesc.width >> irradiancePush.level) > kIrradianceSourceWidth)
        ++irradiancePush.level;
    graph.addPass(
        "environment_irradiance", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(source, gpu::Usage::SampledCompute);
            pass.write(target.irradiance, gpu::Usage::StorageBufferWrite);
        },
        [&device, &irradiance, source, target, irradiancePush](VkCommandBuffer cmd,
                                                                         const gpu::PassResources& res) {
            gpu::DescriptorWriter(device, irradiance)
                .sampled(0, res.view(source), target.sampler)
                .buffer(1, res.buffer(target.irradiance))
                .bind(cmd);
            vkCmdPushConstants(cmd, irradiance.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(irradiancePush),
                               &irradiancePush);
            vkCmdDispatch(cmd, 1, 1, 1);
        });
}

}  // namespace obscura::passes
