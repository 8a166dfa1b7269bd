#include "delegate/frame_scene_source.h"

#include "delegate/api_error.h"
#include "passes/frame_resources.h"

#include <algorithm>

namespace obscura::delegate {

renderer::FrameView FrameSceneSource::view(const renderer::FrameViewpoint& viewpoint) const {
    return frameView(inputs(viewpoint));
}

passes::FrameScene FrameSceneSource::scene(const renderer::FrameViewpoint& viewpoint) {
    FrameSceneShortfalls shortfalls;
    passes::FrameScene scene = buildFrameScene(device_, inputs(viewpoint), shortfalls);
    // The frame's own scene reports; the reference's sub-frames see the same prims.
    if (!viewpoint.sample) report(scene, shortfalls);
    return scene;
}

void FrameSceneSource::culledOnGpu(uint32_t draws, uint64_t instances, uint64_t triangles) {
    report_.culling.drawsCulled += draws;
    report_.culling.instancesCulled += instances;
    report_.culling.trianglesCulled += triangles;
    report_.trianglesDrawn -= std::min(triangles, report_.trianglesDrawn);
}

FrameSceneInputs FrameSceneSource::inputs(const renderer::FrameViewpoint& viewpoint) const {
    FrameSceneInputs inputs = frame_;
    static_cast<renderer::FrameViewpoint&>(inputs) = viewpoint;
    return inputs;
}

void FrameSceneSource::report(const passes::FrameScene& scene, const FrameSceneShortfalls& shortfalls) {
    if (shortfalls.lightsWithoutShadowRoom != report_.lightsWithoutShadowRoom && shortfalls.lightsWithoutShadowRoom > 0)
        log_(LogLevel::Warning, std::to_string(shortfalls.lightsWithoutShadowRoom) +
                                    " light(s) cast no shadow: the shadow atlas is full (lower shadows:resolution)");
    report_.lightsWithoutShadowRoom = shortfalls.lightsWithoutShadowRoom;
    if (shortfalls.unclippedLights != report_.unclippedLights)
        for (const auto& problem : shortfalls.unclippedLights) log_(LogLevel::Warning, problem);
    report_.unclippedLights = shortfalls.unclippedLights;
    if (shortfalls.unresolvedSubsetMaterials != report_.unresolvedSubsetMaterials)
        for (const auto& problem : shortfalls.unresolvedSubsetMaterials) log_(LogLevel::Warning, problem);
    report_.unresolvedSubsetMaterials = shortfalls.unresolvedSubsetMaterials;
    if (scene.instanceCount > passes::kMaxInstanceRecords)
        throw ApiError{OBSCURA_ERROR_OUT_OF_MEMORY, std::to_string(scene.instanceCount) +
                                                        " instances: the G-buffer addresses at most " +
                                                        std::to_string(passes::kMaxInstanceRecords)};
    // What the camera drew: the G-buffer's draws and the transparent ones.
    report_.trianglesDrawn = 0;
    for (const auto& draw : scene.cameraDraws) report_.trianglesDrawn += uint64_t(draw.indexCount / 3) * draw.instanceCount;
    for (uint32_t index : scene.transparentDraws) {
        const passes::Draw& draw = scene.draws[index];
        report_.trianglesDrawn += uint64_t(draw.indexCount / 3) * draw.instanceCount;
    }
    report_.culling = scene.culling;
}

}  // namespace obscura::delegate
