// Data shared by the passes of a frame; mirrors passes/frame_data.h (std430 / std140 layouts).
#ifndef OBSCURA_FRAME_DATA_GLSL
#define OBSCURA_FRAME_DATA_GLSL

struct CameraData {
    mat4 view;
    mat4 projection;
    mat4 viewProjection;
    mat4 inverseViewProjection;
    mat4 inverseProjection;
    vec4 position;       // world-space eye, w unused
    vec2 resolution;     // render size in pixels
    float exposureScale; // camera exposure (UsdGeomCamera linear scale) x 2^(render setting exposure) x a power of two for precision (outputScale): pre-exposed accumulation
    float shutterPosition;  // where within the shutter the frame is seen, 0 open .. 1 close (deforming meshes)
    // Motion blur: world -> clip (unjittered) at the start and end of the part of the shutter the
    // frame blurs over (the whole shutter, or a still's sample's stratum of it); the frame itself
    // is seen at its centre. Without motion blur both are the frame's unjittered view.
    mat4 shutterOpenViewProjection;
    mat4 shutterCloseViewProjection;
    // Temporal AA's sub-pixel shift in clip space (clip.xy += clipJitter * clip.w), already in the
    // matrices above; edge-anti-aliased instances (INSTANCE_EDGE_AA) take it back off.
    vec2 clipJitter;
    // 1 where a dome is seen behind everything (domeLightCameraVisibility): every pixel is covered.
    float backdropCoverage;
    // Where this frame lies in temporal AA's jitter cycle (0 without it): the shadow filter's turn.
    uint noiseFrame;
    // The share of the shutter the velocities span (the stratum's length; 1: the whole shutter).
    float shutterFraction;
    // How MSAA samples resolve (passes/frame_data.h SampleResolve, the SAMPLE_RESOLVE_* below).
    uint sampleResolve;
    // Added to material textures' LOD: -log2(N) / 2 in one of N samples of a still's mean (each
    // lookup filters its own share of the pixel), else 0.
    float textureLodBias;
    // The readback's factor on the accumulated colour: the inverse of the pre-exposure beyond the
    // camera's that exposureScale holds (1 in a scene bright enough for half floats).
    float outputScale;
};

// Mirrors passes/frame_data.h SampleResolve.
const uint SAMPLE_RESOLVE_TONE_MAPPED = 0u;
const uint SAMPLE_RESOLVE_LINEAR = 1u;
const uint SAMPLE_RESOLVE_PIXEL_BOX = 2u;

// One per drawn rprim.
struct InstanceData {
    mat4 model;
    mat4 normalMatrix;   // inverse transpose of model's upper 3x3, in a mat4
    uint materialIndex;
    int primId;
    uint flags;          // INSTANCE_* bits below
    uint motionIndex;    // moving within the shutter: its InstanceMotion record; unused when static
    uint reprojection;   // moved since the last frame: its InstanceReprojection record + 1; 0 unmoved
    int instanceId;      // the instanceId AOV: index in its PointInstancer's arrays, -1 for a plain mesh
    uvec2 displayColor;  // INSTANCE_DISPLAY_COLOR / _OPACITY: half floats (r, g), (b, opacity)
};

// GPU occlusion culling (shaders/occlusion_cull.comp): an instance the camera may draw, its world
// bounds, its InstanceData record and its draw's command (Draw::cullSlot).
struct OcclusionCandidate {
    vec3 boundsMin;
    uint record;
    vec3 boundsMax;
    uint command;
};

// VkDrawIndexedIndirectCommand, where its draw's drawn records start in the list, and its view.
struct CulledDrawCommand {
    uint indexCount;
    uint instanceCount;
    uint firstIndex;
    int vertexOffset;
    uint firstInstance;
    uint listOffset;
    uint view;  // a shadow view's command: the view it draws into
    uint pad0;
};

// Temporal AA's object motion: where an instance that moved since the last frame was then, as
// this frame's world space to last frame's (last model x inverse of this model).
struct InstanceReprojection {
    mat4 currentToPreviousWorld;
};

// Where a moving instance is at the shutter's open and close (motion blur's velocities).
struct InstanceMotion {
    mat4 shutterOpenModel;
    mat4 shutterCloseModel;
};

const uint TEXTURE_CHANNEL_RGB = 4u;  // else 0..3: r, g, b, a
// MaterialTexture::encoding (passes/frame_data.h TexelEncoding).
const uint TEXEL_PLAIN = 0u;
const uint TEXEL_TWO_CHANNEL_NORMAL = 1u;  // x and y; z = sqrt(1 - x^2 - y^2) after scale and bias
const uint TEXEL_SRGB = 2u;                // sRGB-encoded colour, decoded after filtering

// A UsdUVTexture feeding one material input: input = texel * scale + bias.
struct MaterialTexture {
    vec4 scale;
    vec4 bias;
    uint sampled;           // 1: the input reads the draw's texture of its slot, 0: its constant
    uint channel;           // r, g, b, a (0..3) or TEXTURE_CHANNEL_RGB
    uint encoding;          // TEXEL_*: what a filtered texel is decoded from, before scale and bias
    uint transformed;       // 1: transformS and transformT are not the identity
    vec4 transformS;        // xyz: s' = dot(transformS.xyz, vec3(s, t, 1)) (UsdTransform2d, MaterialX tiling)
    vec4 transformT;        // xyz: t' likewise
    vec4 udimGrid;          // a UDIM atlas: st of its lower-left tile square (xy), columns and rows (zw); z 0: one image
};

const uint TEXTURE_DIFFUSE = 0u;
const uint TEXTURE_ROUGHNESS = 1u;
const uint TEXTURE_METALLIC = 2u;
const uint TEXTURE_OPACITY = 3u;
const uint TEXTURE_NORMAL = 4u;
const uint TEXTURE_OCCLUSION = 5u;
const uint TEXTURE_EMISSIVE = 6u;
const uint MATERIAL_TEXTURE_SLOTS = 7u;

struct MaterialData {
    vec4 diffuseRoughness;  // rgb diffuseColor, a roughness
    vec4 emissiveMetallic;  // rgb emissiveColor (textured: the texture's average; the G-buffer's emission target has it), a metallic
    vec4 opacity;           // x opacity, y opacityThreshold, z occlusion
    vec4 specularIor;       // rgb specularColor (specular workflow), a ior
    vec4 clearcoat;         // x clearcoat, y clearcoatRoughness, z 1 for the specular workflow
    vec4 anisotropy;        // x obscura:anisotropy (0: isotropic), y obscura:anisotropyRotation in radians
    MaterialTexture textures[MATERIAL_TEXTURE_SLOTS];
};

const uint LIGHT_DISTANT = 0u;
const uint LIGHT_SPHERE = 1u;
const uint LIGHT_DOME = 2u;
const uint LIGHT_RECT = 3u;
const uint LIGHT_DISK = 4u;
const uint LIGHT_CYLINDER = 5u;

struct LightData {
    vec4 positionType;      // xyz world position (sphere, rect, disk and cylinder centre), w type
    vec4 directionAngle;    // xyz emission axis: the light's local -Z in world space; w half-angle in radians (distant)
    vec4 radiance;          // rgb emitted radiance incl. intensity, exposure, colour, normalize; a radius (sphere, cylinder)
    vec4 factors;           // x diffuse, y specular multipliers; z sphere: 1 for treatAsPoint, cylinder: 1 for
                            // treatAsLine, dome: 1 when it lights
                            // through the environment maps (the textured dome); w influence range (local lights)
    vec4 axisX;             // xyz rect: half the width along local X; disk: the radius along local X; cylinder:
                            // half its length along local X (world space)
    vec4 axisY;             // xyz rect: half the height along local Y; disk: the radius along local Y
    vec4 shaping;           // ShapingAPI: x cone angle, y angle where the soft fade starts (radians), z focus; w unused
    uvec4 shadow;           // x first ShadowViewData record, y their count (0: casts no shadow), z SHADOW_*;
                            // w the clip volume's stencil bit (0: unclipped; passes/clip_volumes.h)
};

const uint SHADOW_CASCADES = 0u;  // a distant light's cascades, by view distance
const uint SHADOW_CUBE = 1u;      // six faces around a local light: +X, -X, +Y, -Y, +Z, -Z
const uint SHADOW_SPOT = 2u;      // one perspective map along the light's axis (a ShapingAPI cone)

// One view of the shadow atlas: a cascade, a cube face or a spot map.
struct ShadowViewData {
    mat4 worldToAtlas;      // world -> clip whose x/w, y/w are atlas texel coordinates, z/w depth
    vec4 tileRect;          // first and last texel of the view's tile: x0, y0, x1, y1
    vec4 params;            // x world size of a texel (perspective: at distance 1), y cascade's far end;
                            // z cascades: world distance along the light of depth 0..1, perspective: near;
                            // w perspective: far
};

// The textured dome's frame (its prefiltered maps and irradiance coefficients are in it).
struct EnvironmentData {
    mat4 worldToDome;       // world directions into the dome's frame: the inverse of its transform
    vec4 params;            // x 1 when a textured dome lights the scene; yzw unused
    // Where nothing is drawn, before exposure: rgb the untextured domes' radiance, w 1 when domes are
    // seen at all; rgb the textured dome's radiance, times its texture (domeLightCameraVisibility).
    vec4 backdrop;
    vec4 texturedBackdrop;
};

// Per-frame records are bound as storage buffers in std140 layout, never as uniform blocks: Mesa
// 22.3's lavapipe inlines uniform-buffer (and push-constant) values that steer a large shader's
// control flow, compiling a new variant at every bind whose values it has not seen and keeping each
// until the device is destroyed (issue 13: ~1.3 MB a frame in the lighting pass, ~0.34 MB a frame
// in temporal AA while a scene is edited). Storage-buffer loads are never inlined.
#define CAMERA_BLOCK(b) layout(set = 0, binding = b, std140) readonly buffer Camera { CameraData camera; }
// The frame's lights (passes/frame_data.h LightBufferHeader): the distant lights first, then the
// domes, then the local lights.
#define LIGHTS_BLOCK(b)                                                                            \
    layout(set = 0, binding = b, std430) readonly buffer Lights {                                  \
        uint lightCount;                                                                           \
        uint distantLightCount;                                                                    \
        uint domeLightCount;                                                                       \
        uint lightPad;                                                                             \
        LightData lights[];                                                                        \
    }
#define ENVIRONMENT_BLOCK(b) layout(set = 0, binding = b, std140) readonly buffer Environment { EnvironmentData environment; }

const uint INSTANCE_DOUBLE_SIDED = 1u;
const uint INSTANCE_VERTEX_COLOR = 2u;
// Hybrid AA (seed 004): drawn unjittered, no temporal history, edges smoothed by the edge AA passes.
const uint INSTANCE_EDGE_AA = 4u;
// Its PointInstancer's primvars give the instance its own displayColor, displayOpacity.
const uint INSTANCE_DISPLAY_COLOR = 8u;
const uint INSTANCE_DISPLAY_OPACITY = 16u;
// The bound material's diffuseColor reads a primvar, served as the vertex colour.
const uint INSTANCE_VERTEX_ALBEDO = 32u;
// The bound material's opacity reads a primvar, served as displayOpacity (the vertex alpha).
const uint INSTANCE_VERTEX_OPACITY = 64u;

// The displayColor (rgb) and displayOpacity (a) a surface without material shows: the vertex's,
// unless the instance has its own (Hydra's instance primvars override the prototype's).
vec4 displayColorOf(InstanceData inst, vec4 vertexColor) {
    vec2 rg = unpackHalf2x16(inst.displayColor.x), ba = unpackHalf2x16(inst.displayColor.y);
    return vec4((inst.flags & INSTANCE_DISPLAY_COLOR) != 0u ? vec3(rg, ba.x) : vertexColor.rgb,
                (inst.flags & INSTANCE_DISPLAY_OPACITY) != 0u ? ba.y : vertexColor.a);
}

// Whether the base colour is displayColorOf's rgb rather than the material's diffuseColor.
bool albedoFromDisplayColor(InstanceData inst) {
    return (inst.flags & (INSTANCE_VERTEX_COLOR | INSTANCE_VERTEX_ALBEDO)) != 0u;
}

// The base colour where albedoFromDisplayColor: a material that reads a primvar scales it by its
// diffuseColor (schemas/material.json obscura:diffuseColor:primvar: 1 for a UsdPrimvarReader, a
// MaterialX surface's weight such as Standard Surface's base); without one it is as it is.
vec3 displayAlbedo(InstanceData inst, vec4 vertexColor, vec3 diffuseColor) {
    vec3 color = displayColorOf(inst, vertexColor).rgb;
    return (inst.flags & INSTANCE_VERTEX_ALBEDO) != 0u ? color * diffuseColor : color;
}

#endif
