// The CPU side of shaders/common/frame_data.glsl: per-frame constants and per-prim records the
// delegate uploads and the passes read. Layouts must match the GLSL (std140 / std430).
#pragma once

#include "generated/shader_layouts.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace obscura::passes {

using Mat4 = std::array<float, 16>;  // column-major, as GLSL's mat4

// How per-sample lighting resolves the MSAA samples of a pixel lit per sample
// (CameraData::sampleResolve; shaders/lighting.comp).
enum class SampleResolve : uint32_t {
    // Tone-mapped weights 1 / (1 + luma) (shaders/common/hdr_resolve.glsl): the seed's resolve for
    // a few samples, which keeps bright edges' coverage in a real-time frame.
    ToneMapped = 0,
    // The plain mean of the pixel's own samples: a sample of a still's mean, which converges to
    // the filtered pixel integral only if every step of it is linear.
    Linear = 1,
    // The plain mean of the samples that fall within the pixel's box this frame, whichever pixel
    // rasterised them: a still's sample under the box filter of width 1. The frame's jitter spans
    // the whole pixel, so each sample's position wraps around the box and the still's samples
    // cover it evenly (the standard pattern's own samples, shifted together, cannot).
    PixelBox = 2,
};

struct alignas(16) CameraData {
    Mat4 view;
    Mat4 projection;
    Mat4 viewProjection;
    Mat4 inverseViewProjection;
    Mat4 inverseProjection;
    std::array<float, 4> position;
    std::array<float, 2> resolution;
    float exposureScale;
    float shutterPosition;  // 0 the shutter's open .. 1 its close: where the frame is seen (deforming meshes)
    Mat4 shutterOpenViewProjection;   // unjittered, for motion blur's velocities
    Mat4 shutterCloseViewProjection;
    // Temporal AA's sub-pixel shift of this frame, in clip space (clip += jitter * w): instances
    // drawn for edge AA (kInstanceEdgeAa) take it back off.
    std::array<float, 2> clipJitter;
    // 1 where the camera sees a dome behind everything (render setting domeLightCameraVisibility):
    // the background is opaque, so every pixel's coverage (the colour AOV's alpha) is 1; else 0.
    float backdropCoverage;
    // Where this frame lies in temporal AA's jitter cycle (0 without temporal AA): the shadow
    // filter turns its taps by it, so a still's mean integrates over the turns
    // (shaders/common/shadow_sampling.glsl).
    uint32_t noiseFrame;
    // The share of the shutter this frame's velocities span, around shutterPosition: 1 in a
    // real-time frame, 1 / taa:frames in a sample of a still's accumulation (the motion AOV
    // divides by it to report the whole shutter's displacement).
    float shutterFraction;
    // SampleResolve: how per-sample lighting resolves a pixel's MSAA samples.
    uint32_t sampleResolve = 0;
    // Added to material textures' LOD: 0 in a real-time frame; -log2(N) / 2 in one of N samples of
    // a still's mean (FrameViewpoint::meanSamples), each lookup filtering its own
    // 1 / N of the pixel so that the mean converges to the pixel's box integral of the texture
    // instead of the box blurred once more by a whole pixel's mip footprint.
    float textureLodBias = 0.0f;
    // What the readback multiplies the accumulated colour by: the inverse of the pre-exposure
    // folded into exposureScale beyond the camera's (delegate/frame_scene_builder.cpp
    // precisionPreExposure), 1 where the scene is bright enough for half floats as it is.
    float outputScale = 1.0f;
};
static_assert(sizeof(CameraData) == 7 * 64 + 16 + 16 + 16 + 16);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, view);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, projection);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, viewProjection);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, inverseViewProjection);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, inverseProjection);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, position);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, resolution);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, exposureScale);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, shutterPosition);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, shutterOpenViewProjection);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, shutterCloseViewProjection);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, clipJitter);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, backdropCoverage);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, noiseFrame);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, shutterFraction);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, sampleResolve);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, textureLodBias);
OBSCURA_SHADER_OFFSET(CameraData, CameraData, outputScale);

// kInstanceEdgeAa: hybrid AA (seed 004) chose edge AA over temporal AA for this instance: it is
// drawn without the jitter, its pixels keep no history and the edge AA passes smooth its edges.
// kInstanceDisplayColor, kInstanceDisplayOpacity: its PointInstancer gives the instance its own
// displayColor, displayOpacity (InstanceData::displayColor), in place of its mesh's; the opacity
// also carries a mesh's constant displayOpacity that a material's primvar reader reads.
// kInstanceVertexColor: Hydra's fallback material (no material bound): the vertex colour is the
// base colour, its alpha the opacity. kInstanceVertexAlbedo: the bound material's diffuseColor
// reads a primvar, served as the vertex colour: its rgb is the base colour. kInstanceVertexOpacity:
// its opacity reads one, served as displayOpacity: the vertex alpha (or the instance's) is the
// opacity.
enum InstanceFlags : uint32_t {
    kInstanceDoubleSided = 1u,
    kInstanceVertexColor = 2u,
    kInstanceEdgeAa = 4u,
    kInstanceDisplayColor = 8u,
    kInstanceDisplayOpacity = 16u,
    kInstanceVertexAlbedo = 32u,
    kInstanceVertexOpacity = 64u,
};

struct alignas(16) InstanceData {
    Mat4 model;
    Mat4 normalMatrix;
    uint32_t materialIndex;
    int32_t primId;
    uint32_t flags;
    uint32_t motionIndex;  // its InstanceMotion record when it moves within the shutter
    uint32_t reprojection = 0;  // moved since the last frame: its InstanceReprojection record + 1
    // The instanceId AOV: the instance's index in its PointInstancer's arrays; -1 for a plain mesh.
    int32_t instanceId = -1;
    // The instance's displayColor and displayOpacity from its PointInstancer's primvars (Hydra's
    // instance primvars), as half floats (packHalf2x16): (r, g), (b, opacity).
    std::array<uint32_t, 2> displayColor{};
};
static_assert(sizeof(InstanceData) == 160);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, model);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, normalMatrix);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, materialIndex);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, primId);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, flags);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, motionIndex);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, reprojection);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, instanceId);
OBSCURA_SHADER_OFFSET(InstanceData, InstanceData, displayColor);

// GPU occlusion culling (passes/occlusion_cull.h): an instance the camera may draw, its world
// bounds, its InstanceData record and its draw's command (Draw::cullSlot).
struct alignas(16) OcclusionCandidate {
    std::array<float, 3> boundsMin;
    uint32_t record;
    std::array<float, 3> boundsMax;
    uint32_t command;
};
static_assert(sizeof(OcclusionCandidate) == 32);
OBSCURA_SHADER_OFFSET(OcclusionCandidate, OcclusionCandidate, boundsMin);
OBSCURA_SHADER_OFFSET(OcclusionCandidate, OcclusionCandidate, record);
OBSCURA_SHADER_OFFSET(OcclusionCandidate, OcclusionCandidate, boundsMax);
OBSCURA_SHADER_OFFSET(OcclusionCandidate, OcclusionCandidate, command);

// VkDrawIndexedIndirectCommand (its first five members), where its draw's drawn records start in
// the culling pass's list, and for a shadow view's draw the view.
struct CulledDrawCommand {
    uint32_t indexCount;
    uint32_t instanceCount;
    uint32_t firstIndex;
    int32_t vertexOffset;
    uint32_t firstInstance;
    uint32_t listOffset;
    uint32_t view = 0;  // a shadow view's command: the view it draws into (ShadowViewData)
    uint32_t pad0 = 0;
};
static_assert(sizeof(CulledDrawCommand) == 32);
OBSCURA_SHADER_OFFSET(CulledDrawCommand, CulledDrawCommand, indexCount);
OBSCURA_SHADER_OFFSET(CulledDrawCommand, CulledDrawCommand, instanceCount);
OBSCURA_SHADER_OFFSET(CulledDrawCommand, CulledDrawCommand, firstIndex);
OBSCURA_SHADER_OFFSET(CulledDrawCommand, CulledDrawCommand, vertexOffset);
OBSCURA_SHADER_OFFSET(CulledDrawCommand, CulledDrawCommand, firstInstance);
OBSCURA_SHADER_OFFSET(CulledDrawCommand, CulledDrawCommand, listOffset);
OBSCURA_SHADER_OFFSET(CulledDrawCommand, CulledDrawCommand, view);

struct alignas(16) InstanceReprojection {
    Mat4 currentToPreviousWorld;  // this frame's world space to last frame's, for temporal AA
};
OBSCURA_SHADER_OFFSET(InstanceReprojection, InstanceReprojection, currentToPreviousWorld);

struct alignas(16) InstanceMotion {
    Mat4 shutterOpenModel;
    Mat4 shutterCloseModel;
};
OBSCURA_SHADER_OFFSET(InstanceMotion, InstanceMotion, shutterOpenModel);
OBSCURA_SHADER_OFFSET(InstanceMotion, InstanceMotion, shutterCloseModel);

// Which texture channel a material input reads: the UsdUVTexture output connected to it.
enum class TextureChannel : uint32_t { R = 0, G = 1, B = 2, A = 3, Rgb = 4 };

// What the shader does with a filtered texel before the UsdUVTexture's scale and bias.
enum class TexelEncoding : uint32_t {
    Plain = 0,
    TwoChannelNormal = 1,  // x and y of a normal map; z is reconstructed after scale and bias
    Srgb = 2,              // sRGB-encoded colour, filtered as encoded and decoded after (delegate/texture_cache.h)
};

// A UsdUVTexture feeding one material input: input = texel * scale + bias (UsdPreviewSurface
// spec, "UsdUVTexture": https://openusd.org/release/spec_usdpreviewsurface.html).
struct alignas(16) MaterialTexture {
    std::array<float, 4> scale{1.0f, 1.0f, 1.0f, 1.0f};
    std::array<float, 4> bias{};
    uint32_t sampled = 0;  // 1: the input reads the draw's texture of its slot, 0: its constant
    uint32_t channel = uint32_t(TextureChannel::R);
    uint32_t encoding = uint32_t(TexelEncoding::Plain);
    uint32_t transformed = 0;   // 1: transformS and transformT are not the identity
    // The texture coordinates' affine map, one row per output: s' = dot(transformS.xyz, (s, t, 1)),
    // t' likewise; w unused. The identity unless UsdTransform2d or MaterialX tiling moved them.
    std::array<float, 4> transformS{1.0f, 0.0f, 0.0f, 0.0f};
    std::array<float, 4> transformT{0.0f, 1.0f, 0.0f, 0.0f};
    // A UDIM set's atlas (delegate/udim_tiles.h): st of its lower-left tile square (x, y) and its
    // columns and rows of squares (z, w); z is 0 for a single image.
    std::array<float, 4> udimGrid{};
};
static_assert(sizeof(MaterialTexture) == 96);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, scale);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, bias);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, sampled);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, channel);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, encoding);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, transformed);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, transformS);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, transformT);
OBSCURA_SHADER_OFFSET(MaterialTexture, MaterialTexture, udimGrid);

// The inputs the G-buffer pass samples, each from its own binding of descriptor set 1. Textured
// emission is written to the G-buffer's emission target, which the lighting pass adds
// (passes/frame_resources.h hasEmissionTarget).
enum MaterialTextureSlot : uint32_t {
    kTextureDiffuse = 0,
    kTextureRoughness = 1,
    kTextureMetallic = 2,
    kTextureOpacity = 3,
    kTextureNormal = 4,  // tangent space, UsdPreviewSurface `normal`
    kTextureOcclusion = 5,
    kTextureEmissive = 6,
    kMaterialTextureSlots = 7
};

struct alignas(16) MaterialData {
    std::array<float, 4> diffuseRoughness;
    std::array<float, 4> emissiveMetallic;  // rgb emissiveColor (textured: its average), a metallic
    std::array<float, 4> opacity;  // x opacity, y opacityThreshold, z occlusion
    std::array<float, 4> specularIor{0.0f, 0.0f, 0.0f, 1.5f};  // rgb specularColor, a ior
    std::array<float, 4> clearcoat{};  // x clearcoat, y clearcoatRoughness, z 1 for the specular workflow
    std::array<float, 4> anisotropy{};  // x obscura:anisotropy, y obscura:anisotropyRotation in radians
    std::array<MaterialTexture, kMaterialTextureSlots> textures;
};
static_assert(sizeof(MaterialData) == 96 + 7 * 96);
OBSCURA_SHADER_OFFSET(MaterialData, MaterialData, diffuseRoughness);
OBSCURA_SHADER_OFFSET(MaterialData, MaterialData, emissiveMetallic);
OBSCURA_SHADER_OFFSET(MaterialData, MaterialData, opacity);
OBSCURA_SHADER_OFFSET(MaterialData, MaterialData, specularIor);
OBSCURA_SHADER_OFFSET(MaterialData, MaterialData, clearcoat);
OBSCURA_SHADER_OFFSET(MaterialData, MaterialData, anisotropy);
OBSCURA_SHADER_OFFSET(MaterialData, MaterialData, textures);

// What a draw's materials use, as a specialization constant of the G-buffer's pipelines
// (shaders/common/material_inputs.glsl MATERIAL_FEATURES): a pipeline leaves out the code of the
// features its draw's materials lack. A CPU device runs every branch of a shader for all lanes of
// its SIMD group, taken or not, so an untextured draw otherwise paid for six texture paths.
enum MaterialFeature : uint32_t {
    kMaterialTextured = 1u,            // some input reads a texture
    kMaterialUdim = 2u,                // some texture is a UDIM set
    kMaterialTransformedTexture = 4u,  // some texture's coordinates are transformed
    kMaterialNormalMap = 8u,           // the normal input reads a texture
    kMaterialAnisotropic = 16u,        // obscura:anisotropy above 0
    kMaterialTexturedEmission = 32u,   // emissiveColor reads a texture: the G-buffer writes it
    kAllMaterialFeatures = 63u,
};
constexpr uint32_t kMaterialFeaturesConstant = 1;  // its constant_id

uint32_t materialFeatures(const MaterialData& material);

enum class LightType : uint32_t { Distant = 0, Sphere = 1, Dome = 2, Rect = 3, Disk = 4, Cylinder = 5 };

struct alignas(16) LightData {
    std::array<float, 4> positionType;
    std::array<float, 4> directionAngle;
    std::array<float, 4> radiance;
    std::array<float, 4> factors;  // z treatAsPoint (sphere), treatAsLine (cylinder) or textured (dome), w influence range
    std::array<float, 4> axisX;
    std::array<float, 4> axisY;
    std::array<float, 4> shaping;
    // x: the light's first ShadowViewData record, y: how many, z: their ShadowProjection;
    // y = 0 when the light casts no shadow; w: the clip volume's stencil bit (0: unclipped).
    std::array<uint32_t, 4> shadow;
};
static_assert(sizeof(LightData) == 8 * 16);
OBSCURA_SHADER_OFFSET(LightData, LightData, positionType);
OBSCURA_SHADER_OFFSET(LightData, LightData, directionAngle);
OBSCURA_SHADER_OFFSET(LightData, LightData, radiance);
OBSCURA_SHADER_OFFSET(LightData, LightData, factors);
OBSCURA_SHADER_OFFSET(LightData, LightData, axisX);
OBSCURA_SHADER_OFFSET(LightData, LightData, axisY);
OBSCURA_SHADER_OFFSET(LightData, LightData, shaping);
OBSCURA_SHADER_OFFSET(LightData, LightData, shadow);

// How a light's shadow views cover it: the cascades of a distant light, the six cube faces
// (+X, -X, +Y, -Y, +Z, -Z) around a local light, or one perspective map along a spot's axis.
enum class ShadowProjection : uint32_t { Cascades = 0, Cube = 1, Spot = 2 };

// The kinds of light a frame holds, as a specialization constant of the lighting pass
// (shaders/common/light_evaluation.glsl LIGHT_KINDS): bit (1 << LightType) for each type present,
// bit (1 << (8 + ShadowProjection)) for each kind of shadow view, and kLightKindShaped where a
// light has a ShapingAPI cone or focus, kLightKindTexturedDome where a dome lights through its
// texture (the environment maps). The lighting pipeline leaves out the code of what the
// frame lacks (see MaterialFeature for why).
constexpr uint32_t kLightKindShaped = 1u << 12;
constexpr uint32_t kLightKindTexturedDome = 1u << 13;
constexpr uint32_t kLightKindsConstant = 2;  // its constant_id
// Whether the lighting pass adds the G-buffer's emission target (passes/frame_resources.h
// GBuffer::emission), a specialization constant of lighting.comp: 1 or 0.
constexpr uint32_t kEmissionTargetConstant = 3;  // its constant_id
uint32_t lightKind(const LightData& light);

// One view of the shadow atlas as the lighting pass reads it (passes/frame_scene.h ShadowMapView).
struct alignas(16) ShadowViewData {
    // World -> atlas: x/w and y/w are atlas texel coordinates, z/w the depth the map stores.
    Mat4 worldToAtlas;
    std::array<float, 4> tileRect;  // first and last texel of the view's tile: x0, y0, x1, y1
    // x: world size of one texel (perspective views: at distance 1 along the view axis);
    // y: cascades: the view distance where the cascade ends; z: cascades: the world distance
    // along the light that the depth range 0..1 spans, perspective views: the near plane; w:
    // perspective views: the far plane (the penumbra's blocker search linearises depth with them).
    std::array<float, 4> params;
};
static_assert(sizeof(ShadowViewData) == 96);
OBSCURA_SHADER_OFFSET(ShadowViewData, ShadowViewData, worldToAtlas);
OBSCURA_SHADER_OFFSET(ShadowViewData, ShadowViewData, tileRect);
OBSCURA_SHADER_OFFSET(ShadowViewData, ShadowViewData, params);

struct alignas(16) EnvironmentData {
    Mat4 worldToDome;
    std::array<float, 4> params;  // x 1 when a textured dome lights the scene
    // What the camera sees where nothing is drawn (render setting domeLightCameraVisibility), before
    // exposure: rgb the untextured domes' radiance, w 1 when domes are seen at all; and rgb the
    // textured dome's radiance, which multiplies its texture.
    std::array<float, 4> backdrop;
    std::array<float, 4> texturedBackdrop;
};
static_assert(sizeof(EnvironmentData) == 112);
OBSCURA_SHADER_OFFSET(EnvironmentData, EnvironmentData, worldToDome);
OBSCURA_SHADER_OFFSET(EnvironmentData, EnvironmentData, params);
OBSCURA_SHADER_OFFSET(EnvironmentData, EnvironmentData, backdrop);
OBSCURA_SHADER_OFFSET(EnvironmentData, EnvironmentData, texturedBackdrop);

// Header of the light buffer: the counts, padded to the first LightData. The lights come sorted:
// the distant lights, then the domes, then the local lights (the lighting pass's loops over each).
struct alignas(16) LightBufferHeader {
    uint32_t count;
    uint32_t distantCount;
    uint32_t domeCount;
    uint32_t pad;
};
static_assert(offsetof(LightBufferHeader, count) == shader_layout::Lights::lightCount);
static_assert(offsetof(LightBufferHeader, distantCount) == shader_layout::Lights::distantLightCount);
static_assert(offsetof(LightBufferHeader, domeCount) == shader_layout::Lights::domeLightCount);
static_assert(sizeof(LightBufferHeader) == shader_layout::Lights::lights);

// Vertex layout of the G-buffer pass.
struct Vertex {
    float position[3];
    float normal[3];
    float color[4];  // primvars:displayColor (rgb) and primvars:displayOpacity (a)
    float uv[2];  // primvars:st as authored (origin at the bottom left); the shader flips v
    // Direction of increasing u on the surface (xyz) and the bitangent's handedness (w = +-1):
    // the frame tangent-space normal maps are read in.
    float tangent[4];
};
static_assert(sizeof(Vertex) == 64);

// Where a deforming mesh's drawn vertices are at the shutter's open and close (motion blur): a
// second vertex stream beside Vertex, one per drawn vertex.
struct ShutterPositions {
    float open[3];
    float close[3];
};
static_assert(sizeof(ShutterPositions) == 24);

}  // namespace obscura::passes
