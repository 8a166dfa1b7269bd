#include "delegate/frame_scene_builder.h"

#include "delegate/prims/instancer.h"
#include "delegate/prims/light.h"
#include "delegate/prims/material.h"
#include "delegate/prims/mesh.h"
#include "passes/clip_volumes.h"
#include "passes/frame_data.h"

#include <Imath/half.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

namespace obscura::delegate {
namespace {

// Camera and environment constants: std140 storage buffers, never uniform blocks
// (shaders/common/frame_data.glsl, CAMERA_BLOCK, says why).
constexpr VkBufferUsageFlags kFrameConstantsUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

template <typename T>
gpu::BufferPtr uploadRecords(gpu::Device& device, const void* header, size_t headerSize, const std::vector<T>& records,
                             VkBufferUsageFlags usage, const char* name) {
    // Never empty: a binding without a resource is an error.
    size_t size = std::max<size_t>(headerSize + records.size() * sizeof(T), sizeof(T));
    auto buffer = device.createFrameBuffer(size, usage, name);
    auto* dst = static_cast<char*>(buffer->mapped());
    std::memset(dst, 0, size);
    if (headerSize) std::memcpy(dst, header, headerSize);
    if (!records.empty()) std::memcpy(dst + headerSize, records.data(), records.size() * sizeof(T));
    return buffer;
}

// GLSL's packHalf2x16: `low` in the low 16 bits, each rounded to the nearest half float.
uint32_t packHalves(float low, float high) {
    return uint32_t(Imath::half(low).bits()) | uint32_t(Imath::half(high).bits()) << 16;
}

// The inverse transpose of the upper 3x3, in the shader's mat4 layout.
Matrix4d normalMatrix(const Matrix4d& model) {
    Matrix4d linear = model;
    linear[12] = linear[13] = linear[14] = 0.0;
    Matrix4d inverse = kIdentity;
    if (!invert(linear, inverse)) return kIdentity;
    return transpose(inverse);
}

// The textured dome's frame: world directions into it (the inverse of its transform's rotation;
// translation and scale mean nothing for a dome at infinity, and normalising the looked-up
// direction removes the scale).
passes::EnvironmentData environmentData(const Light* dome) {
    passes::EnvironmentData data{};
    data.worldToDome = toFloats<passes::Mat4>(kIdentity);
    if (!dome) return data;
    Matrix4d linear = dome->transform();
    linear[12] = linear[13] = linear[14] = 0.0;
    Matrix4d inverse = kIdentity;
    if (invert(linear, inverse)) data.worldToDome = toFloats<passes::Mat4>(inverse);
    data.params = {1.0f, 0.0f, 0.0f, 0.0f};
    return data;
}

double shutterCentre(const std::array<double, 2>& shutter) { return 0.5 * (shutter[0] + shutter[1]); }

// The time codes a motion-blurred frame covers: its span of the shutter (std::lerp returns the
// ends exactly, so a whole span is the shutter itself).
std::array<double, 2> blurInterval(const FrameSceneInputs& in) {
    const auto [open, close] = *in.shutter;
    return {std::lerp(open, close, in.shutterSpan[0]), std::lerp(open, close, in.shutterSpan[1])};
}

}  // namespace

const Light* environmentDome(const std::map<std::string, std::unique_ptr<Prim>>& prims,
                             std::vector<std::string>& ignored) {
    const Light* chosen = nullptr;
    for (const auto& [path, prim] : prims) {
        auto* light = dynamic_cast<const Light*>(prim.get());
        if (!light || light->skipped() || !light->visible() || !light->environment()) continue;
        if (chosen) ignored.push_back(path);
        else chosen = light;
    }
    return chosen;
}

FrameView frameView(const FrameSceneInputs& in) {
    const Camera& cam = in.camera;
    double aspect = double(in.width) * in.pixelAspectRatio / double(in.height);
    if (!in.sample) {
        // A still's frame seen from its stratum of the aperture shears like a reference sub-frame.
        const std::array<double, 2> noJitter{0.0, 0.0};
        Matrix4d projection = in.lensOffset == noJitter ? cam.projectionMatrix(aspect)
                                                        : cam.projectionMatrix(aspect, in.lensOffset, noJitter);
        if (in.shutter) return {cam.viewMatrix(in.lensOffset, shutterCentre(blurInterval(in))), projection};
        Matrix4d lensShift = kIdentity;
        lensShift[12] = -in.lensOffset[0];
        lensShift[13] = -in.lensOffset[1];
        return {multiply(cam.viewMatrix(), lensShift), projection};
    }
    std::array<double, 2> ndcJitter{2.0 * in.sample->pixelJitter[0] / in.width, 2.0 * in.sample->pixelJitter[1] / in.height};
    return {cam.viewMatrix(in.sample->lensOffset, in.sample->time),
            cam.projectionMatrix(aspect, in.sample->lensOffset, ndcJitter)};
}

namespace {

// The most precisionPreExposure brightens, in stops: far within a float's range.
constexpr double kMaxPreExposureStops = 64.0;

// Packs one frame's scene, step by step in the order the records depend on each other: the
// camera (and its motion), materials and lights, the camera constants, the draws (batched meshes,
// then instancers' prototypes), the transparent order, the shadow atlas, clip volumes, the dome.
class FrameScenePacker {
public:
    FrameScenePacker(gpu::Device& device, const FrameSceneInputs& in, FrameSceneShortfalls& shortfalls)
        : device_(device), in_(in), shortfalls_(shortfalls) {}

    passes::FrameScene pack() {
        scene_.width = in_.width + 2 * in_.guardPixels;
        scene_.height = in_.height + 2 * in_.guardPixels;
        packCamera();
        packMaterialsAndLights();
        uploadCamera();
        packDraws();
        packInstancedDraws();
        cullOccluded();
        orderTransparents();
        packShadowAtlas();
        packClipVolumes();
        uploadBuffers();
        packEnvironment();
        return std::move(scene_);
    }

private:
    // The frame's view (the camera's, or a reference sub-frame's), then temporal AA's jitter for
    // everything that rasterises or reads the G-buffer; shadow cascades keep the unjittered
    // frustum, so their texel grids do not move with the jitter. With motion blur, where the
    // camera is at both ends of the part of the shutter the frame blurs over.
    void packCamera() {
        const Camera& cam = in_.camera;
        auto [view, unjitteredProjection] = frameView(in_);
        view_ = view;
        unjitteredProjection_ = unjitteredProjection;
        // The guard band widens the view by its pixels on every side, keeping the pixels' size.
        Matrix4d guardWidening = kIdentity;
        guardWidening[0] = double(in_.width) / scene_.width;
        guardWidening[5] = double(in_.height) / scene_.height;
        Matrix4d projection = multiply(multiply(unjitteredProjection, guardWidening), in_.clipJitter);
        Matrix4d cameraToWorld = kIdentity;
        invert(view, cameraToWorld);
        // When the frame is seen: a sub-frame's time, the centre of the shutter's part it blurs
        // over, or the sync time (none).
        if (in_.shutter && !in_.sample) blurred_ = blurInterval(in_);
        if (in_.sample) frameTime_ = in_.sample->time;
        else if (in_.shutter) frameTime_ = shutterCentre(blurred_);
        Matrix4d viewProjection = multiply(view, projection);
        Matrix4d inverseViewProjection = kIdentity;
        invert(viewProjection, inverseViewProjection);
        passes::CameraData& cd = cd_;
        cd.view = toFloats<passes::Mat4>(view);
        cd.projection = toFloats<passes::Mat4>(projection);
        cd.viewProjection = toFloats<passes::Mat4>(viewProjection);
        cd.inverseViewProjection = toFloats<passes::Mat4>(inverseViewProjection);
        Matrix4d inverseProjection = kIdentity;
        invert(projection, inverseProjection);
        cd.inverseProjection = toFloats<passes::Mat4>(inverseProjection);
        eye_ = transformPoint({0, 0, 0}, cameraToWorld);
        // How far from the eye the near plane reaches (its corners, the lens's shear included):
        // geometry nearer may be clipped by it. Orthographic views: unbounded.
        const Matrix4d& p = unjitteredProjection;
        nearReach_ = cam.params().orthographic
                         ? std::numeric_limits<double>::infinity()
                         : cam.params().clippingRange[0] * std::hypot(1.0, (1.0 + std::abs(p[8])) / std::abs(p[0]),
                                                                      (1.0 + std::abs(p[9])) / std::abs(p[5]));
        cd.position = {float(eye_[0]), float(eye_[1]), float(eye_[2]), 1.0f};
        cd.resolution = {float(scene_.width), float(scene_.height)};
        cd.exposureScale = float(cam.linearExposureScale() * std::exp2(in_.exposureStops));
        cd.shutterOpenViewProjection = cd.shutterCloseViewProjection =
            toFloats<passes::Mat4>(multiply(view, unjitteredProjection));
        cd.shutterPosition = float(0.5 * (in_.shutterSpan[0] + in_.shutterSpan[1]));
        cd.shutterFraction = float(in_.shutterSpan[1] - in_.shutterSpan[0]);
        cd.clipJitter = {float(in_.clipJitter[12]), float(in_.clipJitter[13])};
        cd.noiseFrame = in_.noiseFrame;
        cd.sampleResolve = uint32_t(in_.sampleResolve);
        // N stratified samples each stand for 1 / N of the pixel's area: a footprint 1 / sqrt(N) as wide.
        cd.textureLodBias = float(-0.5 * std::log2(double(std::max(in_.meanSamples, 1u))));
        if (in_.shutter && in_.sample && (*in_.shutter)[1] > (*in_.shutter)[0])
            cd.shutterPosition =
                float((in_.sample->time - (*in_.shutter)[0]) / ((*in_.shutter)[1] - (*in_.shutter)[0]));
        if (in_.shutter && !in_.sample) {
            for (int end = 0; end < 2; ++end) {
                Matrix4d atEnd = multiply(cam.viewMatrix(in_.lensOffset, blurred_[size_t(end)]), unjitteredProjection);
                (end == 0 ? cd.shutterOpenViewProjection : cd.shutterCloseViewProjection) = toFloats<passes::Mat4>(atEnd);
            }
            cameraMoves_ = cd.shutterOpenViewProjection != cd.shutterCloseViewProjection;
        }
    }

    Matrix4d transformOf(const Mesh& mesh) const {
        return frameTime_ ? mesh.transformAt(*frameTime_) : mesh.transform();
    }
    // Where a mesh's transform is at the shutter's open and close, for meshes that move or deform
    // within it (motion blur's velocities); static meshes have none. A reference sub-frame draws
    // deforming meshes between their shutter positions, through the same records.
    std::optional<std::array<Matrix4d, 2>> motionOf(const Mesh& mesh) const {
        if (!in_.shutter) return std::nullopt;
        if (in_.sample) {
            if (!mesh.shutterPositions()) return std::nullopt;
            return std::array<Matrix4d, 2>{transformOf(mesh), transformOf(mesh)};
        }
        std::array<Matrix4d, 2> ends{mesh.transformAt(blurred_[0]), mesh.transformAt(blurred_[1])};
        if (ends[0] == ends[1] && !mesh.shutterPositions()) return std::nullopt;
        return ends;
    }
    gpu::BufferPtr shutterPositionsOf(const Mesh& mesh) const {
        return in_.shutter ? mesh.shutterPositions() : nullptr;
    }

    // Materials (index 0 is the fallback for meshes without a valid binding) with their textures
    // (element 0, all white, serves untextured materials), and the visible lights.
    void packMaterialsAndLights() {
        materials_.resize(1);
        materials_[0].diffuseRoughness = {0.18f, 0.18f, 0.18f, 0.5f};
        materials_[0].opacity = {1.0f, 0, 1.0f, 0};
        passes::MaterialTextures white;
        white.images.fill(in_.textures.white());
        white.samplers.fill(in_.textures.sampler(WrapMode::Repeat, WrapMode::Repeat));
        scene_.materialTextures = {white};
        for (const auto& [path, prim] : in_.prims) {
            if (prim->skipped()) continue;
            if (auto* m = dynamic_cast<const Material*>(prim.get())) {
                materialIndex_[path] = static_cast<uint32_t>(materials_.size());
                if (!m->diffusePrimvar().empty() || !m->opacityPrimvar().empty())
                    primvarReads_[uint32_t(materials_.size())] = {!m->diffusePrimvar().empty(),
                                                                  !m->opacityPrimvar().empty()};
                materials_.push_back(m->data());
                passes::MaterialTextures textures = white;
                for (uint32_t slot = 0; slot < passes::kMaterialTextureSlots; ++slot)
                    if (const auto& bound = m->textures()[slot]) {
                        textures.images[slot] = bound->texture->image;
                        textures.samplers[slot] = bound->sampler;
                    }
                if (std::any_of(m->textures().begin(), m->textures().end(), [](const auto& t) { return t.has_value(); })) {
                    texturesOfMaterial_[path] = static_cast<uint32_t>(scene_.materialTextures.size());
                    scene_.materialTextures.push_back(textures);
                }
            } else if (auto* l = dynamic_cast<const Light*>(prim.get())) {
                if (l->visible()) {
                    lights_.push_back(frameTime_ ? l->dataAt(*frameTime_) : l->data());
                    lightCastsShadows_.push_back(l->castsShadows());
                    lightPrims_.push_back(l);
                    if (l == in_.environmentDome) lights_.back().factors[2] = 1.0f;
                }
            }
        }
        const double preExposure = precisionPreExposure();
        cd_.exposureScale = float(cd_.exposureScale * preExposure);
        cd_.outputScale = float(1.0 / preExposure);
        for (passes::LightData& light : lights_) {
            light = withInfluenceRange(light, cd_.exposureScale);
            if (in_.sample) light = emitterSample(light, in_.sample->emitter);
        }
    }

    // Half floats (the light accumulation, a still's mean) hold normal numbers down to 2^-14 only;
    // a scene lit far more dimly than irradiance 1 (an unnormalised distant light's intensity is
    // its disc's radiance: 0.75 over the sun's 0.53 degrees gives 5e-5) lands among their
    // subnormals, whose fixed steps cost a still of such a scene 3.5 dB against a path tracer. So
    // the accumulation is pre-exposed beyond the camera's exposure (Lagarde & de Rousiers 2014,
    // "Moving Frostbite to PBR", 5.1 "Pre-exposure") by the power of two that brings the brightest
    // light or emissive surface to between 1/2 and 1, and the readback takes it back off: exactly,
    // powers of two being exact. Never below 1, so a scene bright enough keeps its bits as they were;
    // from the lights and materials alone, so every sub-frame and every frame of a still agrees.
    double precisionPreExposure() const {
        double brightest = 0.0;
        for (const passes::LightData& light : lights_) brightest = std::max(brightest, brightestIrradiance(light));
        for (const passes::MaterialData& m : materials_)
            brightest = std::max(brightest, std::numbers::pi * std::max({m.emissiveMetallic[0], m.emissiveMetallic[1],
                                                                          m.emissiveMetallic[2], 0.0f}));
        const double exposed = brightest * cd_.exposureScale;
        if (!(exposed > 0.0) || exposed >= 1.0 || !std::isfinite(exposed)) return 1.0;
        return std::exp2(std::min(std::floor(-std::log2(exposed)), kMaxPreExposureStops));
    }

    // Hydra's domeLightCameraVisibility: a visible dome is the background, opaque.
    void uploadCamera() {
        if (in_.domeBackdrop)
            for (const passes::LightData& light : lights_)
                if (light.positionType[3] == float(passes::LightType::Dome)) cd_.backdropCoverage = 1.0f;
        scene_.cameraData = cd_;
        scene_.camera = device_.createFrameBuffer(sizeof(cd_), kFrameConstantsUsage, "camera");
        std::memcpy(scene_.camera->mapped(), &cd_, sizeof(cd_));
    }

    // The material record a mesh's part draws with: its bound material's, else Hydra's fallback
    // material (displayColor as the vertex colour, the default grey's other inputs) with the mesh's
    // constant displayOpacity, one record per opacity (record 0: opaque).
    std::optional<uint32_t> boundMaterial(const MaterialPart& part) const {
        if (!part.material) return std::nullopt;
        auto it = materialIndex_.find(*part.material);
        return it == materialIndex_.end() ? std::nullopt : std::optional(it->second);
    }
    uint32_t materialOf(const Mesh& mesh, const MaterialPart& part) {
        if (auto bound = boundMaterial(part)) return *bound;
        auto [it, added] = fallbackMaterials_.emplace(mesh.displayOpacity(), uint32_t(materials_.size()));
        if (added) {
            passes::MaterialData fallback = materials_[0];
            fallback.opacity[0] = mesh.displayOpacity();
            materials_.push_back(fallback);
        }
        return it->second;
    }
    // passes::materialFeatures of record `index` of materials_, found once a record (fallback
    // records join materials_ as instances ask for them).
    uint32_t featuresOfMaterial(uint32_t index) {
        for (size_t i = materialFeatures_.size(); i < materials_.size(); ++i)
            materialFeatures_.push_back(passes::materialFeatures(materials_[i]));
        return materialFeatures_[index];
    }
    // A draw's instances share its part's material, and so its textures.
    uint32_t texturesOf(const MaterialPart& part) const {
        if (!part.material) return 0;
        auto it = texturesOfMaterial_.find(*part.material);
        return it == texturesOfMaterial_.end() ? 0 : it->second;
    }
    // Whether a bound material reads primvars the host serves as displayColor and displayOpacity
    // (Material::diffusePrimvar, opacityPrimvar), which a PointInstancer may give each instance;
    // found once per material as the frame packs them, looked up per instance record.
    struct PrimvarReads {
        bool color = false, opacity = false;
    };
    PrimvarReads primvarReads(std::optional<uint32_t> bound) const {
        const auto it = bound ? primvarReads_.find(*bound) : primvarReads_.end();
        return it == primvarReads_.end() ? PrimvarReads{} : it->second;
    }
    // Cut-outs (opacityThreshold) discard texels in the G-buffer and the shadow maps alike.
    bool hasCutout(const Mesh& mesh, const MaterialPart& part) {
        return materials_[materialOf(mesh, part)].opacity[1] > 0.0f;
    }
    // UsdPreviewSurface opacity without a threshold blends (the spec: opacityThreshold 0 means no
    // masking): below 1, or textured, the surface is transparent. So is a prim without a material
    // whose displayOpacity is below 1 anywhere.
    bool isTransparent(const Mesh& mesh, const MaterialPart& part) {
        const passes::MaterialData& m = materials_[materialOf(mesh, part)];
        // XXX: with an opacityThreshold the primvar's opacity cuts nothing out (blending only).
        const bool readsOpacity = primvarReads(boundMaterial(part)).opacity && m.opacity[1] <= 0.0f;
        if ((!boundMaterial(part) || readsOpacity) && mesh.hasTranslucentVertices()) return true;
        if (readsOpacity && mesh.displayOpacity() < 1.0f) return true;
        return m.opacity[1] <= 0.0f && (m.opacity[0] < 1.0f || m.textures[passes::kTextureOpacity].sampled != 0);
    }
    const Mesh* drawable(const Prim& prim) const {
        auto* mesh = dynamic_cast<const Mesh*>(&prim);
        return mesh && !mesh->skipped() && mesh->drawable() && (mesh->purpose() & in_.includedPurposes) ? mesh : nullptr;
    }
    // Prototype meshes draw only through their instancers.
    bool isPrototype(const std::string& path) const {
        for (const Instancer* inst : instancers_)
            if (inst->prototypeOf(path) >= 0) return true;
        return false;
    }

    // A material subset bound to a path that is no material draws with the fallback material, as
    // an unresolved binding does; said once per frame that has it.
    void noteUnresolved(const MaterialPart& part) {
        if (part.subset.empty() || !part.material || boundMaterial(part)) return;
        std::string problem = part.subset + ": material:binding names " + *part.material +
                              ", which is not a material; its faces draw with the fallback material";
        auto& unresolved = shortfalls_.unresolvedSubsetMaterials;
        if (std::find(unresolved.begin(), unresolved.end(), problem) == unresolved.end()) unresolved.push_back(problem);
    }

    // One instance record of a mesh's part. `key`: the instance's identity from frame to frame
    // beside its prim's id (an instancer's ordinal and the instance's number), for temporal AA's
    // object motion; none for records that are not drawn into the G-buffer (clip volumes).
    // `display`: what its instancer's primvars give the instance in place of the mesh's displayColor
    // and displayOpacity.
    void record(const Mesh& mesh, const MaterialPart& part, const Matrix4d& model,
                const std::optional<std::array<Matrix4d, 2>>& motion = std::nullopt, std::optional<uint64_t> key = 0,
                int32_t instanceId = -1, const Instancer::InstanceDisplay& display = {}) {
        passes::InstanceData inst{};
        inst.instanceId = instanceId;
        if (motion) {
            inst.motionIndex = static_cast<uint32_t>(motions_.size());
            motions_.push_back({toFloats<passes::Mat4>((*motion)[0]), toFloats<passes::Mat4>((*motion)[1])});
        }
        if (in_.models && key) {
            uint64_t identity = *key | uint64_t(uint32_t(mesh.primId())) << 32;
            (*in_.models)[identity] = model;
            auto last = in_.lastModels ? in_.lastModels->find(identity) : InstanceModels::const_iterator{};
            Matrix4d inverse = kIdentity;
            if (in_.lastModels && last != in_.lastModels->end() && last->second != model && invert(model, inverse)) {
                // Row vectors: p_last = p_world x model^-1 x lastModel.
                reprojections_.push_back({toFloats<passes::Mat4>(multiply(inverse, last->second))});
                inst.reprojection = static_cast<uint32_t>(reprojections_.size());
            }
        }
        inst.model = toFloats<passes::Mat4>(model);
        inst.normalMatrix = toFloats<passes::Mat4>(normalMatrix(model));
        inst.primId = mesh.primId();
        inst.materialIndex = materialOf(mesh, part);
        scene_.draws.back().materialFeatures |= featuresOfMaterial(inst.materialIndex);
        // UsdPreviewSurface wins over displayColor; without a material, displayColor is the
        // surface colour (as Hydra's fallback material). A material whose diffuseColor (opacity)
        // reads a primvar takes the vertex colour (alpha) the host served it as, and the
        // instance's displayColor (displayOpacity), which the host serves from the instancer's
        // primvar of the name read (Hydra's instance primvars).
        const std::optional<uint32_t> bound = boundMaterial(part);
        const PrimvarReads reads = primvarReads(bound);
        if (!bound) inst.flags |= passes::kInstanceVertexColor;
        if (reads.color) inst.flags |= passes::kInstanceVertexAlbedo;
        if (reads.opacity) inst.flags |= passes::kInstanceVertexOpacity;
        const bool instanceColor = display.color && (!bound || reads.color);
        std::optional<float> opacity = display.opacity && (!bound || reads.opacity) ? display.opacity : std::nullopt;
        // A constant displayOpacity the reader is served stays out of the mesh's vertices.
        if (!opacity && reads.opacity && mesh.displayOpacity() < 1.0f) opacity = mesh.displayOpacity();
        if (instanceColor || opacity) {
            const std::array<float, 3> color = display.color.value_or(std::array<float, 3>{});
            inst.displayColor = {packHalves(color[0], color[1]), packHalves(color[2], opacity.value_or(1.0f))};
            if (instanceColor) inst.flags |= passes::kInstanceDisplayColor;
            if (opacity) inst.flags |= passes::kInstanceDisplayOpacity;
        }
        if (mesh.doubleSided()) inst.flags |= passes::kInstanceDoubleSided;
        // Hybrid AA, per object (seed 004): near the eye the view vector turns fastest as the camera
        // moves, so view-dependent shading defeats reprojection there; edge AA takes those.
        if (key && in_.edgeAaDistance > 0.0 &&
            distanceTo(transformAabb(mesh.localBounds(), model), eye_) < in_.edgeAaDistance) {
            inst.flags |= passes::kInstanceEdgeAa;
            scene_.edgeAa = true;
        }
        instances_.push_back(inst);
    }

    // Whether a placement keeps the winding of what it places (no mirroring).
    static bool keepsWinding(const Matrix4d& model) {
        return model[0] * (model[5] * model[10] - model[6] * model[9]) -
                   model[1] * (model[4] * model[10] - model[6] * model[8]) +
                   model[2] * (model[4] * model[9] - model[5] * model[8]) >
               0.0;
    }

    // Notes an instance of the last draw, of `mesh` placed by `model` within world `bounds`, for
    // back-face culling: where the placement keeps the winding and the back faces draw what is not
    // wanted or what other faces draw. Not wanted: Mesh::backFacesUnwanted, a single-sided surface's
    // back (UsdGeomGprim's doubleSided off lets renderers "perform backface culling"). Drawn by
    // others: a sphere impostor's cube's, whose near faces answer for every pixel
    // (shaders/common/sphere_impostor.glsl) where it lies wholly beyond the view's near plane — for
    // the camera, clear of the eye by more than the near plane reaches; shadow views cull those alone.
    // XXX: a single-sided surface placed mirrored draws both sides (with the normals it has).
    void noteInstance(const Mesh& mesh, const Matrix4d& model, const Aabb& bounds) {
        passes::Draw& draw = scene_.draws.back();
        const bool winding = keepsWinding(model);
        impostorWinding_.back() = impostorWinding_.back() && winding;
        const bool backCullable =
            draw.sphereImpostors ? distanceTo(bounds, eye_) > nearReach_ : mesh.backFacesUnwanted();
        draw.cullBackFaces = draw.cullBackFaces && winding && backCullable;
    }

    // Starts the notes of a new draw (the last one).
    void startInstanceNotes() {
        passes::Draw& draw = scene_.draws.back();
        draw.cullBackFaces = true;
        impostorWinding_.push_back(draw.sphereImpostors);
    }

    // The draw of a mesh's part, for `instanceCount` records from the next one.
    passes::Draw partDraw(const Mesh& mesh, const MaterialPart& part, size_t instanceCount, bool moving) {
        noteUnresolved(part);
        passes::Draw draw{mesh.vertices(), mesh.indices(), part.indices.count,
                          static_cast<uint32_t>(instances_.size()), static_cast<uint32_t>(instanceCount),
                          texturesOf(part), hasCutout(mesh, part), isTransparent(mesh, part),
                          moving, shutterPositionsOf(mesh)};
        draw.firstIndex = part.indices.first;
        draw.sphereImpostors = mesh.drawsSphereImpostors();
        draw.materialFeatures = 0;  // its instances' materials add theirs (record)
        return draw;
    }

    // Meshes with the same geometry (repeated references share buffers through the geometry
    // cache) and the same textures become one instanced draw, in the order they first appear; a
    // mesh with material subsets draws each material's part on its own.
    void packDraws() {
        for (const auto& [path, prim] : in_.prims)
            if (auto* inst = dynamic_cast<const Instancer*>(prim.get())) {
                allInstancers_.push_back(inst);
                if (!inst->skipped() && inst->visible()) instancers_.push_back(inst);
            }
        using Drawn = std::pair<const Mesh*, const MaterialPart*>;
        std::vector<std::vector<Drawn>> batches;
        std::map<std::tuple<const void*, const void*, uint32_t, uint32_t, uint32_t, bool, bool, const void*>, size_t> batchOf;
        for (const auto& [path, prim] : in_.prims) {
            const Mesh* mesh = drawable(*prim);
            if (!mesh || isPrototype(path)) continue;
            for (const MaterialPart& part : mesh->materialParts()) {
                // Transparent meshes draw one by one: the transparent pass sorts draws, not instances.
                if (isTransparent(*mesh, part)) {
                    batches.push_back({{mesh, &part}});
                    continue;
                }
                // Opaque and cut-out draws stay apart: the shadow maps rasterise them differently;
                // moving and static ones too: only moving draws write velocities.
                auto key = std::make_tuple(static_cast<const void*>(mesh->vertices().get()),
                                           static_cast<const void*>(mesh->indices().get()), part.indices.first,
                                           part.indices.count, texturesOf(part), hasCutout(*mesh, part),
                                           motionOf(*mesh).has_value(),
                                           static_cast<const void*>(shutterPositionsOf(*mesh).get()));
                auto [it, added] = batchOf.emplace(key, batches.size());
                if (added) batches.emplace_back();
                batches[it->second].push_back({mesh, &part});
            }
        }
        for (const auto& batch : batches) {
            const auto [first, firstPart] = batch.front();
            scene_.draws.push_back(partDraw(*first, *firstPart, batch.size(), motionOf(*first).has_value()));
            startInstanceNotes();
            Aabb bounds;
            for (const auto& [mesh, part] : batch) {
                record(*mesh, *part, transformOf(*mesh), motionOf(*mesh));
                instanceBounds_.push_back(transformAabb(mesh->localBounds(), transformOf(*mesh)));
                bounds.merge(instanceBounds_.back());
                noteInstance(*mesh, transformOf(*mesh), instanceBounds_.back());
            }
            drawBounds_.push_back(bounds);
        }
    }

    // One level of a prototype mesh's instancing: the instancer, and which of its prototypes holds
    // the level below (the mesh, or an instancer nested in that prototype).
    struct InstancingLevel {
        const Instancer* instancer;
        size_t prototype;
    };

    // Whether some instancer (drawn or not) has `path` in a prototype; `except` aside.
    bool heldByAnInstancer(const std::string& path, const Instancer* except = nullptr) const {
        return std::any_of(allInstancers_.begin(), allInstancers_.end(),
                           [&](const Instancer* inst) { return inst != except && inst->prototypeOf(path) >= 0; });
    }

    // The drawn instancers that place `path` themselves: those with it in a prototype, less those
    // in whose prototype an instancer nested there places it.
    std::vector<InstancingLevel> placersOf(const std::string& path) const {
        std::vector<InstancingLevel> placers;
        for (const Instancer* inst : instancers_) {
            const int proto = inst->prototypeOf(path);
            if (proto < 0) continue;
            bool nested = false;
            for (const Instancer* inner : allInstancers_)
                nested |= inner != inst && inner->prototypeOf(path) >= 0 && inst->prototypeOf(inner->path()) == proto;
            if (!nested) placers.push_back({inst, size_t(proto)});
        }
        return placers;
    }

    // Every chain of instancers that places a prototype mesh, from one that places it out to one no
    // instancer's prototype holds (UsdGeomPointInstancer prototypes may hold instancers in turn);
    // none for a mesh no drawn instancer places, or whose chain passes a hidden or skipped instancer.
    // Nesting deeper than kMaxInstancingDepth (a cycle: malformed) draws nothing.
    static constexpr int kMaxInstancingDepth = 16;
    std::vector<std::vector<InstancingLevel>> instancingChains(const std::string& path, int depth = 0) const {
        std::vector<std::vector<InstancingLevel>> chains;
        if (depth > kMaxInstancingDepth) return chains;
        for (const InstancingLevel& level : placersOf(path)) {
            if (!heldByAnInstancer(level.instancer->path(), level.instancer)) {
                chains.push_back({level});
                continue;
            }
            for (std::vector<InstancingLevel>& outer : instancingChains(level.instancer->path(), depth + 1)) {
                outer.insert(outer.begin(), level);
                chains.push_back(std::move(outer));
            }
        }
        return chains;
    }

    // Instances of a chain: every combination of one instance at each level.
    static size_t chainInstanceCount(const std::vector<InstancingLevel>& chain) {
        size_t count = 1;
        for (const InstancingLevel& level : chain) count *= level.instancer->instancesOf(level.prototype).size();
        return count;
    }

    // The instance of each level that combination `number` takes, innermost first (the innermost
    // varies fastest).
    static std::vector<size_t> chainInstances(const std::vector<InstancingLevel>& chain, size_t number) {
        std::vector<size_t> picks;
        for (const InstancingLevel& level : chain) {
            const size_t count = level.instancer->instancesOf(level.prototype).size();
            picks.push_back(number % count);
            number /= count;
        }
        return picks;
    }

    // Combination `picks`'s placement: each level's instance transform, innermost first, in the
    // row-vector convention (a nested instancer's placements lie in its holder's prototype space).
    // At the frame's placements, or at absolute time `time`.
    static Matrix4d chainPlacement(const std::vector<InstancingLevel>& chain, const std::vector<size_t>& picks,
                                   std::optional<double> time) {
        Matrix4d placement = kIdentity;
        for (size_t l = 0; l < chain.size(); ++l) {
            const InstancingLevel& level = chain[l];
            placement = multiply(placement, time ? level.instancer->instanceAt(level.prototype, picks[l], *time)
                                                 : level.instancer->instancesOf(level.prototype)[picks[l]]);
        }
        return placement;
    }

    // What the chain's instance primvars give the combination: the innermost level's that has one.
    static Instancer::InstanceDisplay chainDisplay(const std::vector<InstancingLevel>& chain,
                                                   const std::vector<size_t>& picks) {
        Instancer::InstanceDisplay display;
        for (size_t l = 0; l < chain.size(); ++l) {
            const Instancer::InstanceDisplay own = chain[l].instancer->displayOf(chain[l].prototype, picks[l]);
            if (!display.color) display.color = own.color;
            if (!display.opacity) display.opacity = own.opacity;
        }
        return display;
    }

    // One draw per (outermost instancer, prototype mesh, material part): the mesh's transform
    // relative to its prototype, then each level's instance transform, innermost first.
    void packInstancedDraws() {
        std::vector<std::pair<const Mesh*, std::vector<InstancingLevel>>> placed;
        for (const auto& [path, prim] : in_.prims)
            if (const Mesh* mesh = drawable(*prim))
                for (std::vector<InstancingLevel>& chain : instancingChains(path)) placed.emplace_back(mesh, std::move(chain));
        for (size_t ordinal = 0; ordinal < instancers_.size(); ++ordinal) {
            const Instancer* inst = instancers_[ordinal];
            for (const auto& [mesh, chain] : placed) {
                if (chain.back().instancer != inst) continue;
                const size_t count = chainInstanceCount(chain);
                if (count == 0) continue;
                // The prototype's own transform and the placements may both move within the shutter.
                auto meshMotion = motionOf(*mesh);
                const bool placementsMove =
                    in_.shutter && !in_.sample &&
                    std::any_of(chain.begin(), chain.end(), [](const InstancingLevel& l) { return l.instancer->movesWithinShutter(); });
                const bool translucent =
                    std::any_of(chain.begin(), chain.end(), [](const InstancingLevel& l) { return l.instancer->hasTranslucentInstances(); });
                for (const MaterialPart& part : mesh->materialParts()) {
                    scene_.draws.push_back(partDraw(*mesh, part, count, meshMotion.has_value() || placementsMove));
                    // Instances the instancers make translucent take the transparent pass, the draw whole.
                    if ((!boundMaterial(part) || primvarReads(boundMaterial(part)).opacity) && translucent)
                        scene_.draws.back().transparent = true;
                    startInstanceNotes();
                    Aabb bounds;
                    for (size_t number = 0; number < count; ++number) {
                        const std::vector<size_t> picks = chainInstances(chain, number);
                        const Matrix4d placement = chainPlacement(chain, picks, frameTime_);
                        Matrix4d model = multiply(transformOf(*mesh), placement);
                        std::optional<std::array<Matrix4d, 2>> motion;
                        if (placementsMove) {
                            motion.emplace();
                            for (int end = 0; end < 2; ++end)
                                (*motion)[size_t(end)] = multiply(
                                    meshMotion ? (*meshMotion)[size_t(end)] : mesh->transformAt(blurred_[size_t(end)]),
                                    chainPlacement(chain, picks, blurred_[size_t(end)]));
                        } else if (meshMotion) {
                            motion = {{multiply((*meshMotion)[0], placement), multiply((*meshMotion)[1], placement)}};
                        }
                        record(*mesh, part, model, motion, (uint64_t(ordinal + 1) << 24) | (number & 0xFFFFFFu),
                               chain.front().instancer->instanceIndexOf(chain.front().prototype, picks.front()),
                               chainDisplay(chain, picks));
                        instanceBounds_.push_back(transformAabb(mesh->localBounds(), model));
                        bounds.merge(instanceBounds_.back());
                        noteInstance(*mesh, model, instanceBounds_.back());
                    }
                    drawBounds_.push_back(bounds);
                }
            }
        }
    }

    static constexpr double kFrustumGuardPixels = 16.0;

    // View frustum culling, then occlusion culling (seed 004 "Occlusion culling"): each draw's
    // bounds, then each of its instances', against the view and the last frame's coverage buffer
    // reprojected into this view
    // (renderer/coverage_buffer.h). The camera draws what stays; the shadow maps still draw every
    // draw (what the camera cannot see may shadow what it can). Draws moving within the shutter are
    // never culled: their bounds hold one time of it. Transparent draws are culled only whole (the
    // transparent pass sorts draws).
    void cullOccluded() {
        const auto start = std::chrono::steady_clock::now();
        // View frustum culling, always on: a box wholly outside the frustum (its sides grown by a
        // guard band of kFrustumGuardPixels, beyond temporal AA's jitter, MSAA samples and the
        // widest pixel filter) is not drawn by the camera. Exact for the image: nothing outside the
        // frustum reaches a pixel of the G-buffer.
        const Matrix4d guardedFrustum =
            multiply(multiply(view_, unjitteredProjection_),
                     Matrix4d{1.0 / (1.0 + 2.0 * kFrustumGuardPixels / in_.width), 0, 0, 0,  //
                              0, 1.0 / (1.0 + 2.0 * kFrustumGuardPixels / in_.height), 0, 0,  //
                              0, 0, 1, 0,                                                        //
                              0, 0, 0, 1});
        passes::CullingCounts& counts = scene_.culling;
        drawCulled_.assign(scene_.draws.size(), false);
        for (size_t d = 0; d < scene_.draws.size(); ++d) {
            const passes::Draw& draw = scene_.draws[d];
            const uint64_t triangles = draw.indexCount / 3;
            counts.draws += 1;
            counts.instances += draw.instanceCount;
            counts.triangles += triangles * draw.instanceCount;
            // Bounds of a draw moving within the shutter hold one time of it: it is never culled.
            const bool still = !draw.moving && !draw.shutterPositions;
            const renderer::CoverageBuffer* occlusion = still ? in_.occlusion : nullptr;
            const auto outsideView = [&](const Aabb& box) { return still && outsideClipVolume(box, guardedFrustum); };
            const auto occluded = [&](const Aabb& box) { return occlusion && occlusion->hidden(box.min, box.max); };
            if (outsideView(drawBounds_[d])) {
                drawCulled_[d] = true;
                counts.drawsOutsideView += 1;
                counts.instancesOutsideView += draw.instanceCount;
                counts.trianglesOutsideView += triangles * draw.instanceCount;
                continue;
            }
            if (occluded(drawBounds_[d])) {
                drawCulled_[d] = true;
                counts.drawsCulled += 1;
                counts.instancesCulled += draw.instanceCount;
                counts.trianglesCulled += triangles * draw.instanceCount;
                continue;
            }
            if (draw.transparent) continue;
            // On the GPU route every still draw's instances in view are candidates, one alone too.
            const bool gpuCulled = still && in_.gpuOcclusionCulling;
            std::vector<uint32_t> kept;
            uint64_t outside = 0, hidden = 0;
            if (still && (draw.instanceCount > 1 || gpuCulled))
                for (uint32_t i = draw.instanceIndex; i < draw.instanceIndex + draw.instanceCount; ++i) {
                    if (outsideView(instanceBounds_[i])) ++outside;
                    else if (occluded(instanceBounds_[i])) ++hidden;
                    else kept.push_back(i);
                }
            if (!gpuCulled && (!still || draw.instanceCount == 1 || kept.size() == draw.instanceCount)) {
                scene_.cameraDraws.push_back(draw);
                continue;
            }
            counts.instancesOutsideView += outside;
            counts.trianglesOutsideView += triangles * outside;
            counts.instancesCulled += hidden;
            counts.trianglesCulled += triangles * hidden;
            if (kept.empty()) {
                drawCulled_[d] = true;
                if (hidden > 0) counts.drawsCulled += 1;
                else counts.drawsOutsideView += 1;
                continue;
            }
            if (gpuCulled) {
                scene_.cameraDraws.push_back(gpuCandidates(draw, kept));
                continue;
            }
            // The instances kept, as consecutive records after the others.
            passes::Draw compacted = draw;
            compacted.instanceIndex = static_cast<uint32_t>(instances_.size());
            compacted.instanceCount = static_cast<uint32_t>(kept.size());
            for (uint32_t i : kept) instances_.push_back(passes::InstanceData(instances_[i]));
            scene_.cameraDraws.push_back(compacted);
        }
        counts.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (in_.occlusion) counts.milliseconds += in_.occlusion->reprojectionMilliseconds();
    }

    // GPU occlusion culling (passes/occlusion_cull.h): `draw` with its instances `kept` (records)
    // as candidates of the culling pass, which writes the draw's commands numbered by its cullSlot.
    passes::Draw gpuCandidates(const passes::Draw& draw, const std::vector<uint32_t>& kept) {
        passes::Draw culled = draw;
        culled.cullSlot = scene_.gpuCulledDraws++;
        culled.firstCandidate = static_cast<uint32_t>(candidates_.size());
        culled.instanceCount = static_cast<uint32_t>(kept.size());
        for (uint32_t record : kept) candidates_.push_back(candidate(record, culled.cullSlot));
        return culled;
    }

    // The instance record's world bounds as a candidate of the draw numbered `cullSlot`, in single
    // precision rounded outwards: the culling pass never tests a smaller box.
    passes::OcclusionCandidate candidate(uint32_t record, uint32_t cullSlot) const {
        const auto rounded = [](const Vec3d& v, float towards) {
            std::array<float, 3> out{};
            for (size_t c = 0; c < 3; ++c) out[c] = std::nextafter(static_cast<float>(v[c]), towards);
            return out;
        };
        constexpr float kInfinity = std::numeric_limits<float>::infinity();
        const Aabb& box = instanceBounds_[record];
        return {rounded(box.min, -kInfinity), record, rounded(box.max, kInfinity), cullSlot};
    }

    // Transparent draws back to front: the "over" blend needs what lies behind drawn first.
    void orderTransparents() {
        std::vector<std::pair<double, uint32_t>> transparentByDistance;
        for (uint32_t i = 0; i < scene_.draws.size(); ++i) {
            if (!scene_.draws[i].transparent || drawCulled_[i]) continue;
            Vec3d centre = drawBounds_[i].centre();
            Vec3d toEye{centre[0] - eye_[0], centre[1] - eye_[1], centre[2] - eye_[2]};
            transparentByDistance.push_back({toEye[0] * toEye[0] + toEye[1] * toEye[1] + toEye[2] * toEye[2], i});
        }
        // Farthest first; equal distances keep submission order (path order), so the result is stable.
        std::stable_sort(transparentByDistance.begin(), transparentByDistance.end(),
                         [](const auto& a, const auto& b) { return a.first > b.first; });
        for (const auto& [distance, index] : transparentByDistance) scene_.transparentDraws.push_back(index);
    }

    // Shadow maps: the views of every shadow-casting light, and each light's place among them.
    void packShadowAtlas() {
        const Camera& cam = in_.camera;
        ShadowedCamera shadowed{view_, unjitteredProjection_};
        ShadowAtlasBuild shadows = buildShadowAtlas(
            {in_.shadows, shadowed, cam.params().clippingRange[0], cam.params().clippingRange[1], drawBounds_}, lights_,
            lightCastsShadows_);
        shortfalls_.lightsWithoutShadowRoom = shadows.lightsLeftUnshadowed;
        scene_.shadows = std::move(shadows.atlas);
        for (size_t v = 0; v < scene_.shadows.views.size(); ++v) {
            passes::ShadowMapView& view = scene_.shadows.views[v];
            for (uint32_t d : view.draws)
                view.cullBackFaces.push_back(impostorWinding_[d] && beyondNearPlane(drawBounds_[d], shadows.viewProjections[v]));
        }
        if (in_.gpuOcclusionCulling &&
            uint64_t(scene_.shadows.views.size()) * instances_.size() <= passes::kMaxShadowCullingStamps)
            shadowCandidates(shadows.viewProjections);
        scene_.shadows.records =
            upload(nullptr, 0, shadows.records, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "shadow views");
    }

    // GPU occlusion culling of the shadow views (passes/occlusion_cull.h): each still caster's
    // instances inside a view are candidates of its draw into that view. Moving draws (their bounds
    // hold one time of the shutter) and what casts no shadow are drawn as they are.
    void shadowCandidates(const std::vector<Matrix4d>& viewProjections) {
        passes::ShadowAtlas& atlas = scene_.shadows;
        for (size_t v = 0; v < atlas.views.size(); ++v) {
            passes::ShadowMapView& view = atlas.views[v];
            view.culled.resize(view.draws.size());
            for (size_t i = 0; i < view.draws.size(); ++i) {
                const passes::Draw& draw = scene_.draws[view.draws[i]];
                if (draw.transparent || draw.moving || draw.shutterPositions) continue;
                passes::CulledViewDraw& culled = view.culled[i];
                culled.cullSlot = atlas.gpuCulledDraws++;
                culled.firstCandidate = static_cast<uint32_t>(shadowCandidates_.size());
                for (uint32_t record = draw.instanceIndex; record < draw.instanceIndex + draw.instanceCount; ++record)
                    if (!outsideClipVolume(instanceBounds_[record], viewProjections[v]))
                        shadowCandidates_.push_back(candidate(record, culled.cullSlot));
                culled.candidateCount = static_cast<uint32_t>(shadowCandidates_.size()) - culled.firstCandidate;
            }
        }
        if (shadowCandidates_.empty()) return;
        atlas.occlusionCandidateCount = static_cast<uint32_t>(shadowCandidates_.size());
        atlas.occlusionCandidates =
            upload(nullptr, 0, shadowCandidates_, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "shadow occlusion candidates");
    }

    // Clip volumes: each clipped light's mesh gets a stencil bit and an instance record of its own
    // (the mesh may be invisible: it is drawn only into the stencil).
    void packClipVolumes() {
        for (size_t i = 0; i < lights_.size(); ++i) {
            const auto& clip = lightPrims_[i]->clipVolume();
            if (!clip) continue;
            auto it = in_.prims.find(*clip);
            const Mesh* mesh = it == in_.prims.end() ? nullptr : dynamic_cast<const Mesh*>(it->second.get());
            std::string problem = !mesh ? "obscura:clipVolume " + *clip + " is not a mesh"
                                  : mesh->skipped() || !mesh->hasGeometry() ? "clip volume " + *clip + " has no geometry"
                                  : scene_.clipVolumes.size() == passes::kMaxClipVolumes
                                      ? "more than " + std::to_string(passes::kMaxClipVolumes) + " clipped lights"
                                      : std::string();
            if (!problem.empty()) {
                shortfalls_.unclippedLights.push_back(lightPrims_[i]->path() + ": " + problem +
                                                      "; the light is not clipped");
                continue;
            }
            uint32_t bit = 1u << scene_.clipVolumes.size();
            scene_.clipVolumes.push_back({{mesh->vertices(), mesh->indices(), mesh->indexCount(),
                                           static_cast<uint32_t>(instances_.size()), 1, 0, false},
                                          bit});
            // Drawn whole into the stencil: its parts' materials do not matter.
            record(*mesh, mesh->materialParts().front(), mesh->transform(), std::nullopt, std::nullopt);
            lights_[i].shadow[3] = bit;
        }
    }

    template <typename T>
    gpu::BufferPtr upload(const void* header, size_t headerSize, const std::vector<T>& records, VkBufferUsageFlags usage,
                          const char* name) {
        return uploadRecords(device_, header, headerSize, records, usage, name);
    }

    void uploadBuffers() {
        scene_.instanceCount = static_cast<uint32_t>(std::min<size_t>(instances_.size(), UINT32_MAX));
        constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        scene_.instances = upload(nullptr, 0, instances_, storage, "instances");
        scene_.instanceMotions = upload(nullptr, 0, motions_, storage, "instance motions");
        scene_.instanceReprojections = upload(nullptr, 0, reprojections_, storage, "instance reprojections");
        scene_.motionBlur = in_.shutter && !in_.sample && (cameraMoves_ || !motions_.empty());
        scene_.materials = upload(nullptr, 0, materials_, storage, "materials");
        uploadLights();
        if (!candidates_.empty()) {
            scene_.occlusionCandidateCount = static_cast<uint32_t>(candidates_.size());
            scene_.occlusionCandidates = upload(nullptr, 0, candidates_, storage, "occlusion candidates");
        }
    }

    // The light buffer: the distant lights, then the domes, then the local lights, each kind in the
    // stage's order (the lighting pass loops over each kind apart: shaders/lighting.comp).
    void uploadLights() {
        const auto isOf = [](passes::LightType type) {
            return [type](const passes::LightData& light) { return uint32_t(light.positionType[3]) == uint32_t(type); };
        };
        std::vector<passes::LightData> sorted = lights_;
        const auto domes = std::stable_partition(sorted.begin(), sorted.end(), isOf(passes::LightType::Distant));
        const auto locals = std::stable_partition(domes, sorted.end(), isOf(passes::LightType::Dome));
        passes::LightBufferHeader header{uint32_t(sorted.size()), uint32_t(domes - sorted.begin()),
                                         uint32_t(locals - domes), 0};
        scene_.lights = upload(&header, sizeof(header), sorted, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "lights");
        scene_.lightKinds = 0;
        for (const passes::LightData& light : sorted) scene_.lightKinds |= passes::lightKind(light);
    }

    // The dome's frame, and the domes the camera sees: each one's radiance, the textured one's
    // times its texture.
    void packEnvironment() {
        passes::EnvironmentData environment = environmentData(in_.environmentDome);
        if (cd_.backdropCoverage > 0.0f) {
            environment.backdrop[3] = 1.0f;
            for (const passes::LightData& light : lights_) {
                if (light.positionType[3] != float(passes::LightType::Dome)) continue;
                auto& sum = light.factors[2] > 0.5f ? environment.texturedBackdrop : environment.backdrop;
                for (size_t c = 0; c < 3; ++c) sum[c] += light.radiance[c];
            }
        }
        scene_.environment = device_.createFrameBuffer(sizeof(environment), kFrameConstantsUsage, "environment");
        std::memcpy(scene_.environment->mapped(), &environment, sizeof(environment));
        scene_.instanceRecords = std::move(instances_);
        scene_.materialRecords = std::move(materials_);
    }

    gpu::Device& device_;
    const FrameSceneInputs& in_;
    FrameSceneShortfalls& shortfalls_;
    passes::FrameScene scene_;
    // The camera.
    Matrix4d view_ = kIdentity, unjitteredProjection_ = kIdentity;
    Vec3d eye_{};
    double nearReach_ = 0.0;
    // Per draw: sphere impostors whose every instance keeps its cube's winding.
    std::vector<bool> impostorWinding_;
    std::optional<double> frameTime_;
    std::array<double, 2> blurred_{};
    passes::CameraData cd_{};
    bool cameraMoves_ = false;
    // Materials and lights.
    std::vector<passes::MaterialData> materials_;
    std::map<std::string, uint32_t> texturesOfMaterial_;
    std::map<std::string, uint32_t> materialIndex_;
    std::vector<uint32_t> materialFeatures_;  // featuresOfMaterial's, one per record of materials_
    std::map<uint32_t, PrimvarReads> primvarReads_;  // by material record, those whose inputs read primvars
    std::map<float, uint32_t> fallbackMaterials_{{1.0f, 0u}};
    std::vector<passes::LightData> lights_;
    std::vector<bool> lightCastsShadows_;
    std::vector<const Light*> lightPrims_;
    // Draws.
    std::vector<const Instancer*> instancers_;     // drawn: not skipped, visible
    std::vector<const Instancer*> allInstancers_;  // drawn or not: what hides their prototypes
    std::vector<passes::InstanceData> instances_;
    std::vector<passes::InstanceMotion> motions_;
    std::vector<passes::InstanceReprojection> reprojections_;
    std::vector<Aabb> drawBounds_;  // world bounds of each draw, all its instances
    std::vector<Aabb> instanceBounds_;  // world bounds of each drawn instance record
    std::vector<passes::OcclusionCandidate> candidates_;  // GPU occlusion culling's, draw by draw
    std::vector<passes::OcclusionCandidate> shadowCandidates_;  // the shadow views', view by view
    std::vector<bool> drawCulled_;  // occlusion culling hid the whole draw from the camera
};

}  // namespace

passes::FrameScene buildFrameScene(gpu::Device& device, const FrameSceneInputs& in, FrameSceneShortfalls& shortfalls) {
    return FrameScenePacker(device, in, shortfalls).pack();
}

}  // namespace obscura::delegate
