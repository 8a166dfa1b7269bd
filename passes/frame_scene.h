// What the delegate hands to the passes for one frame: GPU buffers of the synced scene and the
// list of draws. Passes read it; they never see prims.
#pragma once

#include "gpu/device.h"
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
};

// The textures a material samples, one per MaterialTextureSlot, white where the input is
// constant (a binding without a resource is an error). The images stay alive with the frame.
struct MaterialTextures {
    std::array<gpu::ImagePtr, kMaterialTextureSlots> images;
    std::array<VkSampler, kMaterialTextureSlots> samplers{};
};

struct FrameScene {
    gpu::BufferPtr camera;     // CameraData (uniform)
    gpu::BufferPtr instances;  // InstanceData[] (storage)
    gpu::BufferPtr materials;  // MaterialData[] (storage)
    gpu::BufferPtr lights;     // LightBufferHeader + LightData[] (storage)
    gpu::BufferPtr environment;  // EnvironmentData (uniform)
    std::vector<MaterialTextures> materialTextures;  // never empty: element 0 is all white
    std::vector<Draw> draws;
    uint32_t width = 0;
    uint32_t height = 0;
};

}  // namespace obscura::passes
