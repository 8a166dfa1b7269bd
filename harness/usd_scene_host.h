// The harness as a Hydra host: a composed USD stage presented to the plugin as prims, with a
// scene-delegate callback table that answers the plugin's pulls (attribute values at a time,
// transforms sampled over an interval). It uses only the public ABI.
#pragma once

#include "harness/delegate_message.h"
#include "harness/material_bind_subsets.h"
#include "harness/material_binding.h"
#include "harness/materialx_surface.h"
#include "harness/native_instancing.h"
#include "harness/shading_network.h"
#include "harness/usda/bezier_curves.h"
#include "harness/usda/skinning.h"
#include "harness/usda/stage.h"

#include <obscura/obscura.h>

#include <array>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace obscura::harness {

// A sphere around what a scene draws (centre and radius in world space).
struct SceneBounds {
    std::array<double, 3> centre{};
    double radius = 0.0;
};

// The render buffer format an AOV needs (the ABI's AOV table).
std::string aovBufferFormat(const std::string& aov);

struct HostMessage {
    bool error;
    std::string text;
    usda::SourceLocation where;  // where the offending prim or attribute is authored; file "" if nowhere
};

class UsdSceneHost {
public:
    explicit UsdSceneHost(const usda::Stage& stage);

    // Inserts every supported prim into the delegate; unknown prim types are reported once each.
    ObscuraStatus populate(const ObscuraApiV1& api, ObscuraDelegate delegate);
    // After the scene's files changed on disk: this host holds the stage read again and `previous`
    // the one the delegate was populated from (and still pulls from until the host's callbacks
    // move to this one). Inserts the prims that are new, removes those that went and marks dirty
    // only what changed in the others (USD's change processing, by comparing the two stages);
    // returns how many prims it touched, through `touched`.
    ObscuraStatus adoptChanges(const UsdSceneHost& previous, const ObscuraApiV1& api, ObscuraDelegate delegate,
                               double time, size_t& touched);
    // Marks dirty the prims whose values change between two time codes (for --frames).
    ObscuraStatus markTimeVarying(const ObscuraApiV1& api, ObscuraDelegate delegate);
    const ObscuraSceneDelegate& sceneDelegate() const { return sceneDelegate_; }

    // Render buffers: one prim per AOV under /Render/Buffers, sized width x height.
    std::string addRenderBuffer(const ObscuraApiV1& api, ObscuraDelegate delegate, const std::string& aov,
                                int width, int height);

    // The first camera of the stage, or "" if there is none.
    std::string defaultCamera() const;
    // The bounding sphere of every point-based prim at `time`, skinned prims posed (the origin, radius
    // 1e-3, for none).
    SceneBounds bounds(double time);
    // Every prim inserted into the delegate, by path, with its delegate type.
    const std::map<std::string, std::string>& insertedPrims() const { return primTypes_; }
    // The PointInstancer whose prototypes hold `path`, or "" (picking names the instancer).
    std::string instancerOf(const std::string& path) const;
    // The instance proxy a native instance's pick names (usdview's): the path of `path`, geometry
    // of a prototype, in instance `instanceId` of its instancer; "" when `path` is no prototype's.
    std::string instanceProxyPath(const std::string& path, int32_t instanceId) const;
    // Native instancing (native_instancing.h): the instancers the host serves.
    const NativeInstancing& nativeInstancing() const { return nativeInstancing_; }
    // For scenes without a camera (typical of OBJ files): inserts a camera that frames the
    // bounds of every mesh at `time` from the front (+Z), as usdview's free camera does.
    std::string addFramingCamera(const ObscuraApiV1& api, ObscuraDelegate delegate, double time);
    const usda::Stage& stage() const { return stage_; }
    const std::vector<HostMessage>& messages() const { return messages_; }
    // Called with each message as it arises (values are checked when the delegate pulls them).
    void setMessageSink(std::function<void(const HostMessage&)> sink) { sink_ = std::move(sink); }
    // Where the prim or attribute a delegate's message is about was authored: the attribute's
    // name in the file, else the prim's definition; nullopt for a prim the stage does not have.
    std::optional<usda::SourceLocation> locate(const PrimMessage& message) const;

private:
    static ObscuraStatus getValueThunk(void* user, const char* path, const char* attribute, double time,
                                       ObscuraValue* out);
    static ObscuraStatus getInterpolationThunk(void* user, const char* path, const char* attribute,
                                               ObscuraInterpolation* out);
    static ObscuraStatus sampleTransformThunk(void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                              double* times, double* matrices, uint32_t* count);
    ObscuraStatus getValue(const std::string& path, const std::string& attribute, double time, ObscuraValue* out);
    // An attribute of `prim` (as resolveAttribute names it) at `time` as the delegate is served it:
    // its connection followed, assets resolved, indices flattened, counts checked, skinned.
    ObscuraStatus authoredValue(const usda::Prim& prim, const std::string& attribute, double time, usda::Value& out);
    // The stage's prims the delegate draws, by path, with their delegate types; fills surfaces_ and
    // prototypeRoots_ and reports what it leaves out.
    std::map<std::string, std::string> scan();
    // The dirty bits that cover how `prim` (of this stage) differs from `before` (of `previous`'s).
    ObscuraDirtyBits changes(const std::string& type, const usda::Prim& prim, const UsdSceneHost& previous, const usda::Prim& before,
                             double time) const;
    ObscuraStatus fill(const usda::Value& value, ObscuraValue* out);
    ObscuraStatus fillToken(const char* token, ObscuraValue* out);
    // The surface shader a Material's outputs:surface (else outputs:mtlx:surface) leads to, through
    // NodeGraph outputs, or null with the reason.
    const usda::Prim* surfaceShader(const usda::Prim& material, std::string& problem) const;
    // UsdSkel: the prim's binding to a skeleton, kept when it is usable, reported when it is not.
    void bindSkeleton(const usda::Prim& prim);
    // A skinned prim's `points` or `normals` (`value`, evaluated at `time`) skinned in place; left as
    // they are, with the problem reported, when the influences do not fit them.
    void applySkinning(const usda::Prim& prim, const usda::Skinning& skinning, const usda::Attribute& attribute,
               usda::Value& value, double time);
    // UsdGeomImageable's computed purpose, inherited from the nearest ancestor that authors one.
    ObscuraStatus computedPurpose(const usda::Prim& prim, ObscuraValue* out);
    // The attribute a delegate name maps to on the USD prim (materials read their surface shader).
    const usda::Attribute* resolveAttribute(const std::string& path, const std::string& attribute) const;
    void warnOnce(const std::string& key, const std::string& text, const usda::SourceLocation& where = {},
                  bool error = false);
    // A problem with a value before it is handed over (an index outside the values, a count that
    // does not fit the topology, an integer that does not fit int32); "" when it is fine.
    std::string primvarCountProblem(const usda::Prim& prim, const usda::Attribute& attribute,
                                    const usda::Value& value, double time) const;

    const usda::Stage& stage_;
    ObscuraSceneDelegate sceneDelegate_{};
    std::map<std::string, std::string> primTypes_;        // delegate path -> delegate type
    std::map<std::string, const usda::Prim*> surfaces_;   // material path -> UsdPreviewSurface shader
    std::map<std::string, usda::Skinning> skinnings_;     // skinned prim path -> its binding
    // Skeletons drawn as guides, as Storm draws them (usda/skeleton_bones.h): each is served as a
    // mesh of purpose guide, which the plugin draws only where includedPurposes names guide.
    std::map<std::string, usda::Skinning> skeletonGuides_;
    void addSkeletonGuide(const usda::Prim& skeleton, std::map<std::string, std::string>& found);
    // The guide mesh's own attributes at `time`; nullopt for what the Skeleton prim answers itself
    // (transform, visibility, displayColor).
    std::optional<ObscuraStatus> skeletonGuideValue(const usda::Skinning& skeleton, const std::string& attribute,
                                                    double time, ObscuraValue* out);
    // NurbsCurves and HermiteCurves served as cubic Bezier basisCurves, TetMeshes as the mesh of
    // their surface (usda/nurbs_curves.h, usda/hermite_curves.h, usda/tet_mesh.h), converted at the
    // time the delegate pulls; a prim whose data the conversion refuses is served empty.
    struct ConvertedPrim {
        double time;
        std::variant<usda::BezierCurves, std::vector<int>, usda::AttributeProblem> form;  // curves, surface triangles
    };
    std::map<std::string, ConvertedPrim> converted_;
    // The converted form of `prim` at `time`, its problem reported once naming the prim; null for a
    // prim of a type served as authored.
    const ConvertedPrim* convertedForm(const usda::Prim& prim, double time);
    // A converted curves prim's Bezier control points from its `points` (authoredValue's) at `time`.
    std::vector<double> bezierControlPoints(const usda::Prim& prim, const usda::BezierCurves& curves,
                                            const usda::Value& points, double time) const;
    // A converted prim's own attributes at `time`; nullopt for what it answers as authored (placement,
    // visibility, purpose, doubleSided...).
    std::optional<ObscuraStatus> convertedValue(const usda::Prim& prim, const std::string& attribute, double time,
                                                ObscuraValue* out);
    // Materials whose surface is not UsdPreviewSurface (MaterialX node definitions, or surfaces
    // drawn with their base colour): their mapping onto UsdPreviewSurface's inputs at one time.
    struct MappedSurface {
        const usda::Prim* shader;
        bool animated;  // its network reads a time-sampled value (isNetworkAnimated)
        std::optional<double> time;
        MaterialXMapping mapping;
    };
    std::map<std::string, MappedSurface> mappedSurfaces_;
    // The dirty bits of the values the prim at `path` serves that are time-sampled (a material's:
    // its surface network's).
    ObscuraDirtyBits animatedValueBits(const std::string& path, const std::string& type, const usda::Prim& prim) const;
    // The mapping of a material's surface at `time` (its problems reported once), or null when the
    // material is not mapped.
    const MaterialXMapping* mappedSurface(const std::string& material, double time);
    // PointInstancer prototype roots -> the prim whose space instances live in (the root's
    // parent: USD includes the root's own transform in each instance, not its ancestors').
    std::map<std::string, const usda::Prim*> prototypeRoots_;
    const usda::Prim* pointInstancerSpace(const usda::Prim& prim) const;
    // The space a prim's transform is served in: a PointInstancer's, or for geometry of a native
    // instance's prototype, the instance's; null for world space.
    const usda::Prim* prototypeSpace(const usda::Prim& prim) const;
    NativeInstancing nativeInstancing_;
    ObscuraStatus getNativeInstancerValue(const NativeInstancer& instancer, const std::string& attribute, double time,
                                          ObscuraValue* out);
    // The material bound to a prim or its nearest ancestor with a binding.
    std::optional<std::string> boundMaterial(const usda::Prim& prim) const;  // material_binding.h
    MaterialBindSubsets bindSubsets(const usda::Prim& mesh, double time) const;
    DrawableMaterial drawableMaterial() const;
    // The UsdPrimvarReader on `input` (inputs:diffuseColor, inputs:opacity) of the UsdPreviewSurface
    // bound to a prim; its primvar is served as the prim's primvars:displayColor, displayOpacity
    // (resolveAttribute).
    std::optional<PrimvarRead> boundPrimvarRead(const usda::Prim& prim, const std::string& input) const;
    std::optional<PrimvarRead> prototypesPrimvarRead(const usda::Prim& instancer, const std::string& input) const;
    struct RenderBufferDesc {
        int width, height;
        std::string format;
    };
    std::map<std::string, RenderBufferDesc> renderBuffers_;
    struct FramingCamera {
        std::string path;
        std::array<double, 16> transform;
        float clippingRange[2];
    };
    std::optional<FramingCamera> framingCamera_;
    std::set<std::string> warned_;
    std::vector<HostMessage> messages_;
    std::function<void(const HostMessage&)> sink_;
    // Storage that backs the values a callback returns, one per calling thread: valid until that
    // thread's next callback (the ABI's lifetime under OBSCURA_SCENE_DELEGATE_THREAD_SAFE).
    struct ReturnedValues {
        std::vector<float> floats;
        std::vector<double> doubles;
        std::vector<int32_t> ints;
        std::vector<std::string> strings;
        std::vector<const char*> stringPointers;
    };
    std::map<std::thread::id, ReturnedValues> returned_;
    ReturnedValues& returned() { return returned_[std::this_thread::get_id()]; }
    // The delegate pulls rprims on several threads (the host is OBSCURA_SCENE_DELEGATE_THREAD_SAFE);
    // the callbacks answer one at a time, as answering builds state lazily (converted prims, mapped
    // surfaces, messages, the returned values' storage).
    std::mutex callbacks_;
};

}  // namespace obscura::harness
