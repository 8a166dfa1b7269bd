// The CPU side of shaders/common/frame_data.glsl: per-frame constants and per-prim records the
// delegate uploads and the passes read. Layouts must match the GLSL (std140 / std430).
#pragma once

#include <array>
#include <cstdint>

namespace obscura::passes {

using Mat4 = std::array<float, 16>;  // column-major, as GLSL's mat4

struct alignas(16) CameraData {
    Mat4 view;
    Mat4 projection;
    Mat4 viewProjection;
    Mat4 inverseViewProjection;
    std::array<float, 4> position;
    std::array<float, 2> resolution;
    float exposureScale;
    float pad0;
};
static_assert(sizeof(CameraData) == 4 * 64 + 16 + 16);

enum InstanceFlags : uint32_t { kInstanceDoubleSided = 1u, kInstanceVertexColor = 2u };

struct alignas(16) InstanceData {
    Mat4 model;
    Mat4 normalMatrix;
    uint32_t materialIndex;
    int32_t primId;
    uint32_t flags;
    uint32_t pad0;
};
static_assert(sizeof(InstanceData) == 144);

struct alignas(16) MaterialData {
    std::array<float, 4> diffuseRoughness;
    std::array<float, 4> emissiveMetallic;
    std::array<float, 4> opacityPad;
};
static_assert(sizeof(MaterialData) == 48);

enum class LightType : uint32_t { Distant = 0, Sphere = 1, Dome = 2 };

struct alignas(16) LightData {
    std::array<float, 4> positionType;
    std::array<float, 4> directionAngle;
    std::array<float, 4> radiance;
    std::array<float, 4> factors;
};
static_assert(sizeof(LightData) == 64);

// Header of the light buffer: the count, padded to the first LightData.
struct alignas(16) LightBufferHeader {
    uint32_t count;
    uint32_t pad[3];
};

// Vertex layout of the G-buffer pass.
struct Vertex {
    float position[3];
    float normal[3];
    float color[3];
};
static_assert(sizeof(Vertex) == 36);

}  // namespace obscura::passes
