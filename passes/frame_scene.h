// What the delegate hands to the passes for one frame: GPU buffers of the synced scene and the
// list of draws. Passes read it; they never see prims.
#pragma once

#include "gpu/device.h"
#include "gpu/frame_graph.h"
#include "passes/frame_data.h"

#include <array>
#include <vector>

namespace obscura::passes {

struct Draw {
    gpu::BufferPtr vertices;
    gpu::BufferPtr indices;   // uint32
    uint32_t indexCount = 0;
    uint32_t instanceIndex = 0;  // first InstanceData record of the draw
    uint32_t instanceCount = 1;  // consecutive records, one per GPU instance
    uint32_t textures = 0;       // the draw's MaterialTextures in FrameScene::materialTextures
    bool opacityCutout = false;  // its material has an opacityThreshold: some texels are absent
    // Its material is partly transparent (opacity below 1 or textured, no opacityThreshold):
    // drawn by the forward transparent pass, not into the G-buffer or the shadow maps.
    bool transparent = false;
    bool moving = false;         // its instances move within the shutter (motion blur's velocities)
    gpu::BufferPtr shutterPositions;  // deforming: ShutterPositions per vertex (moving draws only)
    // Its triangles are cubes bounding spheres (UsdGeomPoints): the passes draw the spheres they
    // bound, ray-cast per pixel (shaders/common/sphere_impostor.glsl).
    bool sphereImpostors = false;
    // The G-buffer and the transparent pass may cull back faces, where every instance keeps its
    // winding: single-sided surfaces, and sphere impostors whose cubes lie clear of the eye and the
    // near plane, so only their near faces answer.
    bool cullBackFaces = false;
    // Where the draw's indexCount indices start in `indices`: a mesh whose faces bind several
    // materials (GeomSubsets) draws each material's range of one index buffer.
    uint32_t firstIndex = 0;
    // GPU occlusion culling (passes/occlusion_cull.h): the draw's instanceCount instances are the
    // candidates from firstCandidate on in FrameScene::occlusionCandidates, and the culling pass
    // writes the instances it draws into the commands numbered cullSlot. kNotCulledOnGpu: drawn
    // as it is, its records from instanceIndex on.
    static constexpr uint32_t kNotCulledOnGpu = UINT32_MAX;
    uint32_t cullSlot = kNotCulledOnGpu;
    uint32_t firstCandidate = 0;
    bool culledOnGpu() const { return cullSlot != kNotCulledOnGpu; }
    // What its instances' materials use (frame_data.h materialFeatures, or-ed): the G-buffer's
    // pipeline leaves the rest out.
    uint32_t materialFeatures = kAllMaterialFeatures;
};

// The textures a material samples, one per MaterialTextureSlot, white where the input is
// constant (a binding without a resource is an error). The images stay alive with the frame.
struct MaterialTextures {
    std::array<gpu::ImagePtr, kMaterialTextureSlots> images;
    std::array<VkSampler, kMaterialTextureSlots> samplers{};
};

// One view of the shadow atlas (a cascade of a distant light, a cube face of a sphere light): a
// square tile the shadow-map pass renders the view's draws into, depth only.
// GPU occlusion culling of one draw into one shadow view: like Draw::cullSlot and firstCandidate,
// its candidates among ShadowAtlas::occlusionCandidates.
struct CulledViewDraw {
    uint32_t cullSlot = Draw::kNotCulledOnGpu;
    uint32_t firstCandidate = 0;
    uint32_t candidateCount = 0;
};

struct ShadowMapView {
    Mat4 viewProjection{};        // world -> clip of the view
    uint32_t x = 0, y = 0;        // the tile's first texel in the atlas
    uint32_t size = 0;            // the tile's side in texels
    std::vector<uint32_t> draws;  // indices into FrameScene::draws whose bounds reach the view
    // One per draw of `draws`: the view may cull its back faces (a sphere impostor draw whose
    // instances keep their cubes' winding, wholly beyond the view's near plane); empty: none.
    std::vector<bool> cullBackFaces;
    // Under GPU occlusion culling, one per draw of `draws` (cullSlot kNotCulledOnGpu: drawn as it
    // is, every instance); empty otherwise.
    std::vector<CulledViewDraw> culled;
};

// Every shadow map of the frame in one depth image; lights find their views through
// LightData's shadow field and the ShadowViewData records.
struct ShadowAtlas {
    uint32_t width = 1;  // texels; 1x1 (cleared to the far depth) when no light casts shadows
    uint32_t height = 1;
    std::vector<ShadowMapView> views;
    gpu::BufferPtr records;  // ShadowViewData[] (storage), one per view, never empty
    // GPU occlusion culling: OcclusionCandidate[] (storage) of the views' culled draws, each
    // culled draw's consecutive (its command is its cullSlot); null when none is.
    gpu::BufferPtr occlusionCandidates;
    uint32_t occlusionCandidateCount = 0;
    uint32_t gpuCulledDraws = 0;
};

// The stamps of shadow views are kept per view and instance record: beyond this many, the views
// are not culled on the GPU.
constexpr uint64_t kMaxShadowCullingStamps = uint64_t(1) << 24;

// A light's clip volume (passes/clip_volumes.h): a closed mesh rasterised into one stencil bit.
struct ClipVolume {
    Draw draw;           // one instance, its record holding the mesh's transform
    uint32_t stencilBit;  // 0x01..0x40; the light's LightData names the same bit
};

// The scene's records (FrameScene's buffers) as resources of the frame graph they are wired into
// (importSceneBuffers): passes bind and declare these like any other resource.
struct SceneBuffers {
    gpu::BufferHandle camera;
    gpu::BufferHandle instances;
    gpu::BufferHandle instanceMotions;
    gpu::BufferHandle instanceReprojections;
    gpu::BufferHandle materials;
    gpu::BufferHandle lights;
    gpu::BufferHandle environment;
    gpu::BufferHandle shadowRecords;
    gpu::BufferHandle occlusionCandidates;  // unset when no draw is culled on the GPU
    gpu::BufferHandle shadowCandidates;     // unset when no shadow view's draw is
};

// An indexed draw whose command a pass wrote into a buffer (VkDrawIndexedIndirectCommand at `offset`).
struct IndirectDraw {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
};

// What GPU occlusion culling hands the G-buffer and the shadow maps (passes/occlusion_cull.h): for
// each draw culled on the GPU (Draw::cullSlot, CulledViewDraw::cullSlot) an indexed indirect
// command per phase, and the records they draw.
struct CulledDraws {
    enum class Phase { Early, Late };
    Phase phase = Phase::Early;
    // The shadow atlas's draws (ShadowAtlas::occlusionCandidates, CulledViewDraw), not the camera's.
    bool shadowViews = false;
    uint32_t drawCount = 0;      // draws culled on the GPU: the commands of one phase
    uint32_t candidateCount = 0;  // FrameScene::occlusionCandidateCount
    gpu::BufferHandle commands;  // CulledDrawCommand[2 * drawCount]: the early phase's, then the late one's
    gpu::BufferHandle lists;     // record indices, each command's from its listOffset

    // Which of `commands` is the draw's of `cullSlot` in this phase, and where the drawn records of
    // the draw whose candidates start at `firstCandidate` start in `lists`: the early phase's at
    // its first candidate, the late one's as many further as there are candidates.
    uint32_t command(uint32_t cullSlot) const { return (phase == Phase::Late ? drawCount : 0) + cullSlot; }
    uint32_t listOffset(uint32_t firstCandidate) const {
        return (phase == Phase::Late ? candidateCount : 0) + firstCandidate;
    }
};

// Occlusion culling's tally of a frame's camera draws (render setting occlusionCulling): before
// culling, and what the coverage buffer hid (a draw culled whole, or instances of one).
struct CullingCounts {
    uint32_t draws = 0;
    uint32_t drawsCulled = 0;
    uint64_t instances = 0;
    uint64_t instancesCulled = 0;
    uint64_t triangles = 0;
    uint64_t trianglesCulled = 0;
    double milliseconds = 0.0;  // CPU time of the tests
    // Outside the view frustum (not counted in the culled counts above, which are the coverage
    // buffer's).
    uint32_t drawsOutsideView = 0;
    uint64_t instancesOutsideView = 0;
    uint64_t trianglesOutsideView = 0;
};

struct FrameScene {
    CameraData cameraData{};   // what `camera` holds, for passes that build push constants
    gpu::BufferPtr camera;     // CameraData (uniform)
    gpu::BufferPtr instances;  // InstanceData[] (storage)
    gpu::BufferPtr instanceMotions;  // InstanceMotion[] (storage) of the moving instances, never empty
    // InstanceReprojection[] (storage) of the instances that moved since the last frame (temporal
    // AA's object motion), never empty.
    gpu::BufferPtr instanceReprojections;
    gpu::BufferPtr materials;  // MaterialData[] (storage)
    gpu::BufferPtr lights;     // LightBufferHeader + LightData[] (storage)
    uint32_t lightKinds = ~0u;  // the kinds `lights` holds (frame_data.h lightKind, or-ed)
    gpu::BufferPtr environment;  // EnvironmentData (uniform)
    std::vector<MaterialTextures> materialTextures;  // never empty: element 0 is all white
    // What `instances` and `materials` hold, on the CPU: for passes that cache their results
    // and must know whether what they draw changed (the shadow atlas).
    std::vector<InstanceData> instanceRecords;
    std::vector<MaterialData> materialRecords;
    std::vector<Draw> draws;  // every draw of the scene: what the shadow maps draw from
    // The opaque and cut-out draws the camera draws into the G-buffer: `draws` less what occlusion
    // culling hid; an instanced draw may keep some of its instances (their records copied after
    // the others').
    std::vector<Draw> cameraDraws;
    uint32_t instanceCount = 0;  // InstanceData records in `instances`
    // The transparent draws (indices into `draws`) the camera draws, back to front: by the distance
    // from the eye to the centre of each draw's world bounds (an instanced draw sorts as one).
    std::vector<uint32_t> transparentDraws;
    CullingCounts culling;
    // GPU occlusion culling: OcclusionCandidate[] (storage) of the draws culled on the GPU, each
    // draw's consecutive from its firstCandidate; null when none is.
    gpu::BufferPtr occlusionCandidates;
    uint32_t occlusionCandidateCount = 0;
    uint32_t gpuCulledDraws = 0;  // draws with a cullSlot: 0 .. gpuCulledDraws - 1
    ShadowAtlas shadows;
    std::vector<ClipVolume> clipVolumes;
    // Motion blur: the G-buffer writes the velocities of the moving draws (drawn last) and the
    // motion blur passes run. Set when the frame asks for motion blur and the camera or an
    // instance moves within the shutter.
    bool motionBlur = false;
    // Hybrid AA: some instance carries kInstanceEdgeAa, so the edge AA passes run after temporal AA.
    bool edgeAa = false;
    uint32_t width = 0;
    uint32_t height = 0;
    // The buffers above in the frame graph being wired: set by importSceneBuffers.
    SceneBuffers buffers;
};

}  // namespace obscura::passes
