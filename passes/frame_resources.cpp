#include "passes/frame_resources.h"

#include <algorithm>

namespace obscura::passes {

void importSceneBuffers(gpu::FrameGraph& graph, FrameScene& scene) {
    scene.buffers = {graph.importBuffer("camera", scene.camera),
                     graph.importBuffer("instances", scene.instances),
                     graph.importBuffer("instanceMotions", scene.instanceMotions),
                     graph.importBuffer("instanceReprojections", scene.instanceReprojections),
                     graph.importBuffer("materials", scene.materials),
                     graph.importBuffer("lights", scene.lights),
                     graph.importBuffer("environment", scene.environment),
                     graph.importBuffer("shadowRecords", scene.shadows.records)};
    if (scene.occlusionCandidates)
        scene.buffers.occlusionCandidates = graph.importBuffer("occlusionCandidates", scene.occlusionCandidates);
    if (scene.shadows.occlusionCandidates)
        scene.buffers.shadowCandidates = graph.importBuffer("shadowCandidates", scene.shadows.occlusionCandidates);
}

bool hasEmissionTarget(const FrameScene& scene) {
    return std::any_of(scene.cameraDraws.begin(), scene.cameraDraws.end(), [](const Draw& d) {
        return !d.transparent && (d.materialFeatures & kMaterialTexturedEmission) != 0u;
    });
}

GBuffer createGBufferImages(gpu::FrameGraph& graph, const FrameScene& scene, VkSampleCountFlagBits samples,
                            const std::string& prefix) {
    auto image = [&](const char* name, VkFormat format) {
        gpu::ImageDesc desc;
        desc.format = format;
        desc.width = scene.width;
        desc.height = scene.height;
        desc.samples = samples;
        return graph.createImage(prefix + "." + name, desc);
    };
    GBuffer gb{image("depth", gbufferDepthFormat(samples)), image("normalRoughness", kNormalRoughnessFormat),
               image("albedoMetallic", kAlbedoMetallicFormat), image("instance", kInstanceFormat), {}};
    if (scene.motionBlur) gb.velocity = image("velocity", kVelocityFormat);
    if (hasEmissionTarget(scene)) gb.emission = image("emission", kEmissionFormat);
    return gb;
}

}  // namespace obscura::passes
