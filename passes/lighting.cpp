#include "passes/lighting.h"

#include "passes/shader_pass.h"

namespace obscura::passes {
namespace {

constexpr uint32_t kLightingTileSize = 16;  // lighting.comp's TILE_SIZE: one workgroup culls lights per tile

}  // namespace

gpu::ImageHandle addLightingPass(gpu::FrameGraph& graph, const FrameScene& scene, const GBuffer& gb,
                                 const SsaoResult& ambient, gpu::ImageHandle shadowAtlas,
                                 const EnvironmentLighting& environment, LightAccumulation format,
                                 const PerSampleLighting* perSample) {
    gpu::ImageDesc desc;
    desc.format = format == LightAccumulation::HalfFloat ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                         : VK_FORMAT_B10G11R11_UFLOAT_PACK32;
    desc.width = scene.width;
    desc.height = scene.height;
    gpu::ImageHandle accumulation = graph.createImage("lightAccumulation", desc);
    ComputePass pass{"lighting",
                     {bufferRead(scene.buffers.camera), bufferRead(scene.buffers.instances),
                      bufferRead(scene.buffers.materials), bufferRead(scene.buffers.lights), sampled(gb.depth),
                      sampled(gb.normalRoughness), sampled(gb.albedoMetallic), sampled(gb.instance),
                      storageWrite(accumulation), sampled(ambient.accessibility), sampled(ambient.halfDepth),
                      bufferRead(scene.buffers.shadowRecords), sampled(shadowAtlas),
                      gb.stencil.valid() ? sampled(gb.stencil) : sampledStencil(gb.depth),
                      bufferRead(scene.buffers.environment), bufferRead(environment.irradiance),
                      sampled(environment.prefiltered, environment.sampler)}};
    // The PER_SAMPLE_LIGHTING build of lighting.comp: the multisampled G-buffer and the tagged count.
    if (perSample) {
        const GBuffer& samples = perSample->multisampled;
        pass.bindings.insert(pass.bindings.end(),
                             {sampled(samples.depth), sampled(samples.normalRoughness),
                              sampled(samples.albedoMetallic), sampled(samples.instance),
                              bufferWrite(perSample->taggedPixelCount)});
    }
    // The textured emission, the multisampled G-buffer's where lighting reads samples. Without one,
    // the albedo stands in for the binding, and the EMISSION_TARGET specialization reads nothing.
    const GBuffer& emissive = perSample ? perSample->multisampled : gb;
    const bool emission = emissive.emission.valid();
    pass.bindings.push_back(sampled(emission ? emissive.emission : emissive.albedoMetallic));
    pass.shader = perSample ? "lighting_per_sample" : "lighting";
    // Built for the kinds of light the frame holds (frame_data.h lightKind): without shadow views,
    // without the shadow lookups.
    pass.specialization = {{kLightKindsConstant, scene.lightKinds}, {kEmissionTargetConstant, emission ? 1u : 0u}};
    pass.texelsPerGroup = {kLightingTileSize, kLightingTileSize};
    pass.label = "lighting";
    return addComputePass(graph, std::move(pass)).images[0];
}

}  // namespace obscura::passes
