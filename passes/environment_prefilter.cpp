#include "passes/environment_prefilter.h"

#include "generated/shader_layouts.h"
#include "passes/shader_pass.h"

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

EnvironmentLighting addEnvironmentPrefilterPasses(gpu::FrameGraph& graph, gpu::ImageHandle source,
                                                  const EnvironmentLighting& target) {
    const gpu::ImageDesc sourceDesc = graph.imageDesc(source);
    const double sourceLevels = double(sourceDesc.mipLevels);
    const PrefilterPush common{
        0.0f,
        float(std::clamp(std::log2(double(sourceDesc.width) / double(kPrefilteredWidth)), 0.0, sourceLevels - 1.0)),
        float(4.0 * std::numbers::pi / (double(sourceDesc.width) * double(sourceDesc.height))),
        float(sourceLevels - 1.0)};
    // Levels are independent (each reads only the source): no barrier between dispatches.
    std::vector<ComputePass> levels;
    const gpu::ImageDesc prefiltered = graph.imageDesc(target.prefiltered);
    for (uint32_t level = 0; level < kPrefilteredLevels; ++level) {
        PrefilterPush push = common;
        push.roughness = float(level) / float(kPrefilteredLevels - 1);
        ComputePass pass{"environment_prefilter",
                         {sampled(source, target.sampler), storageWriteLevel(target.prefiltered, level)},
                         bytesOf(push)};
        pass.texels = std::array<uint32_t, 2>{std::max(prefiltered.width >> level, 1u),
                                              std::max(prefiltered.height >> level, 1u)};
        levels.push_back(std::move(pass));
    }
    EnvironmentLighting written = target;
    written.prefiltered = addComputeDispatches(graph, kEnvironmentPrefilterPass, std::move(levels)).images[0];

    IrradiancePush irradiancePush{0};
    while (uint32_t(irradiancePush.level) + 1 < sourceDesc.mipLevels &&
           (sourceDesc.width >> irradiancePush.level) > kIrradianceSourceWidth)
        ++irradiancePush.level;
    ComputePass irradiance{"environment_irradiance",
                           {sampled(source, target.sampler), bufferWrite(target.irradiance)},
                           bytesOf(irradiancePush)};
    irradiance.texels = std::array<uint32_t, 2>{1, 1};  // one workgroup projects the whole source
    irradiance.texelsPerGroup = {1, 1};
    written.irradiance = addComputePass(graph, std::move(irradiance)).buffers[0];
    return written;
}

}  // namespace obscura::passes
