#include "harness/usd_scene_host.h"

#include "harness/material_bind_subsets.h"
#include "harness/materialx_surface.h"
#include "harness/omni_pbr_surface.h"
#include "harness/shading_network.h"
#include "harness/usda/hermite_curves.h"
#include "harness/usda/matrix4.h"
#include "harness/usda/nurbs_curves.h"
#include "harness/usda/skeleton_bones.h"
#include "harness/usda/skinning.h"
#include "harness/usda/tet_mesh.h"
#include "schemas/schema.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <variant>

namespace obscura::harness {
namespace {

// USD prim type -> Obscura prim type.
const std::map<std::string, std::string> kPrimTypes = {
    {"Mesh", "mesh"},
    {"Camera", "camera"},
    {"DistantLight", "distantLight"},
    {"SphereLight", "sphereLight"},
    {"RectLight", "rectLight"},
    {"DiskLight", "diskLight"},
    {"CylinderLight", "cylinderLight"},
    {"DomeLight", "domeLight"},
    {"DomeLight_1", "domeLight"},  // turned to its poleAxis (domePoleTurn)
    {"Material", "material"},
    {"PointInstancer", "instancer"},
    {"Cube", "cube"},
    {"Sphere", "sphere"},
    {"Cylinder", "cylinder"},
    {"Cylinder_1", "cylinder1"},
    {"Cone", "cone"},
    {"Capsule", "capsule"},
    {"Capsule_1", "capsule1"},
    {"Plane", "plane"},
    {"BasisCurves", "basisCurves"},
    {"NurbsPatch", "nurbsPatch"},
    {"Points", "points"},
    // Served converted, as UsdImaging's adapters serve them (convertedValue): curves as cubic
    // Bezier basis curves, a TetMesh as the mesh of its surface.
    {"NurbsCurves", "basisCurves"},
    {"HermiteCurves", "basisCurves"},
    {"TetMesh", "mesh"},
};

// Attributes of the types served converted that the plugin does not read under their own names,
// and the served attribute each feeds: its dirty bit makes the plugin read the conversion again.
const std::map<std::pair<std::string, std::string>, std::string> kConvertedInputs = {
    {{"NurbsCurves", "order"}, "curveVertexCounts"},
    {{"NurbsCurves", "knots"}, "curveVertexCounts"},
    {{"NurbsCurves", "ranges"}, "curveVertexCounts"},
    {{"NurbsCurves", "pointWeights"}, "curveVertexCounts"},  // rational spans are cut into pieces by them
    {{"HermiteCurves", "tangents"}, "points"},
    {{"TetMesh", "tetVertexIndices"}, "faceVertexIndices"},
    {{"TetMesh", "surfaceFaceVertexIndices"}, "faceVertexIndices"},
    {{"DomeLight_1", "poleAxis"}, "transform"},
};

// The primvars a prim is served from the UsdPrimvarReader on an input of its material, by the name
// the plugin reads them under, with the reader's default where neither the prim nor the reader has
// a value (UsdPreviewSurface spec: zero).
struct ServedRead {
    std::string input;
    usda::Attribute zero;
};
usda::Attribute zeroFallback(const char* type, int components) {
    usda::Value zero;
    zero.typeName = type;
    zero.tupleSize = components;
    zero.numbers = std::vector<double>(size_t(components), 0.0);
    return usda::Attribute{"inputs:fallback", type, false, false, std::move(zero)};
}
const std::map<std::string, ServedRead> kServedReads = {
    {"primvars:displayColor", {"inputs:diffuseColor", zeroFallback("float3", 3)}},
    {"primvars:displayOpacity", {"inputs:opacity", zeroFallback("float", 1)}},
};

bool isConvertedCurves(const std::string& type) { return type == "NurbsCurves" || type == "HermiteCurves"; }

// Types that organise a scene and are not drawn themselves.
// UsdSkel's prims pose the prims they skin (usda/skinning.h).
// GeomSubsets of the materialBind family are served as part of their mesh (material_bind_subsets.h).
// A Skeleton is served as its bones' guide mesh (addSkeletonGuide).
// A PortalLight "guides sampling of a dome light" (UsdLux): a sampler's hint, and the dome's
// prefiltered light (environment_map.glsl) is the integral it would converge to.
// Schemas no viewport draws: UsdPhysics' scene, joints and collision groups (simulation data, as
// Omniverse assets carry), UsdMedia's SpatialAudio, UsdUI's Backdrop, and UsdVol's field assets,
// which are a Volume's inputs (the Volume is reported).
const std::set<std::string> kStructuralTypes = {"",
                                                "Xform",
                                                "Scope",
                                                "Shader",
                                                "NodeGraph",
                                                "GeomSubset",
                                                "RenderSettings",
                                                "RenderProduct",
                                                "RenderVar",
                                                "RenderPass",
                                                "SkelRoot",
                                                "SkelAnimation",
                                                "BlendShape",
                                                "PortalLight",
                                                "PhysicsScene",
                                                "PhysicsCollisionGroup",
                                                "PhysicsJoint",
                                                "PhysicsFixedJoint",
                                                "PhysicsRevoluteJoint",
                                                "PhysicsPrismaticJoint",
                                                "PhysicsSphericalJoint",
                                                "PhysicsDistanceJoint",
                                                "SpatialAudio",
                                                "Backdrop",
                                                "OpenVDBAsset",
                                                "Field3DAsset"};

// UsdLuxDomeLight_1's `poleAxis`: its dome's top pole along the stage's up axis ("scene", the
// fallback), +Y or +Z. The plugin's dome has its pole along local +Y, as UsdLuxDomeLight's; a +Z
// pole is that dome turned +90 degrees about X before its own transform (as
// UsdLuxDomeLight::OrientToStageUpAxis turns one), for the dome alone: its children do not inherit it.
// A token outside the allowed ones is reported through `bad` and taken as "scene".
usda::Matrix4 domePoleTurn(const usda::Stage& stage, const usda::Prim& prim,
                           const std::function<void(const usda::Attribute&, const std::string&)>& bad) {
    if (prim.typeName != "DomeLight_1") return usda::matrix4::identity();
    std::string pole = "scene";
    if (const usda::Attribute* a = prim.attribute("poleAxis"))
        if (auto v = a->evaluate(0.0); v && !v->strings.empty()) {
            pole = v->strings[0];
            if (pole != "scene" && pole != "Y" && pole != "Z") {
                bad(*a, pole);
                pole = "scene";
            }
        }
    if (pole == "scene") pole = stage.metadata().upAxis;
    return pole == "Z" ? usda::matrix4::rotation(0, 90.0) : usda::matrix4::identity();
}

bool isPointBased(const std::string& type) {
    return type == "Mesh" || type == "BasisCurves" || type == "Points" || type == "NurbsPatch" || isConvertedCurves(type) ||
           type == "TetMesh";
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Whether the plugin draws `prim` as geometry (an rprim; a Skeleton as its guide mesh) that an
// instancer can place: what native instancing instances (native_instancing.h).
bool isInstancedGeometry(const usda::Prim& prim) {
    if (prim.typeName == "Skeleton") return true;
    const auto it = kPrimTypes.find(prim.typeName);
    if (it == kPrimTypes.end() || it->second == "instancer") return false;
    const schema::PrimSchema* schema = schema::findPrimSchema(it->second);
    return schema && std::strcmp(schema->category, "rprim") == 0;
}

// The dirty bit that makes the plugin read attribute `name` of a prim of plugin type `type` again:
// the schema's (schemas/*.json), under the names this host serves it by: a light input also by
// its name before UsdLux 21.02 (no "inputs:"), and a primvar the schema does not name may be the
// one the material's textures read, served as primvars:st, or one its diffuseColor or opacity
// reads, served as primvars:displayColor or displayOpacity (one dirty bit). 0: the plugin does not
// read it.
ObscuraDirtyBits dirtyBitFor(const std::string& type, const std::string& name) {
    const schema::PrimSchema* prim = schema::findPrimSchema(type);
    if (!prim) return 0;
    const schema::AttributeSchema* attribute = schema::findAttribute(*prim, name);
    if (!attribute) attribute = schema::findAttribute(*prim, "inputs:" + name);
    if (!attribute && startsWith(name, "primvars:")) attribute = schema::findAttribute(*prim, "primvars:st");
    if (!attribute && startsWith(name, "primvars:")) attribute = schema::findAttribute(*prim, "primvars:displayColor");
    return attribute ? attribute->dirtyBit : 0;
}

// The same for USD attribute `name` of `prim`, under the name it is served by (kConvertedInputs).
ObscuraDirtyBits attributeDirtyBit(const usda::Prim& prim, const std::string& type, const std::string& name) {
    const auto converted = kConvertedInputs.find({prim.typeName, name});
    return dirtyBitFor(type, converted == kConvertedInputs.end() ? name : converted->second);
}

// Values with one element per point, curve, segment end or face (UsdGeomPrimvar's interpolations):
// what a converted prim serves converted.
bool isPerElement(const std::string& name) {
    return name == "points" || name == "velocities" || name == "accelerations" || name == "widths" ||
           name == "normals" || startsWith(name, "primvars:");
}

// UsdGeomPrimvar's interpolation as authored on `attribute`; "" when it is not.
std::string authoredInterpolation(const usda::Attribute& attribute) {
    const auto authored = attribute.metadata.find("interpolation");
    return authored == attribute.metadata.end() || authored->second.strings.empty() ? "" : authored->second.strings.front();
}

// UsdGeomPrimvar's elementSize as authored on `attribute` (1 when it is not).
size_t elementSizeOf(const usda::Attribute& attribute) {
    const auto authored = attribute.metadata.find("elementSize");
    return authored == attribute.metadata.end() || authored->second.numbers.empty()
               ? 1
               : size_t(std::max(1.0, authored->second.numbers.front()));
}

// The interpolation of a converted curves' attribute: as authored, else the plugin schema's fallback
// for the attribute it is served as (widths and normals vertex, displayColor constant), else
// UsdGeomPrimvar's (constant) for other primvars and vertex for point data (velocities).
std::string curvesInterpolation(const usda::Attribute& attribute, const std::string& name) {
    if (std::string authored = authoredInterpolation(attribute); !authored.empty()) return authored;
    const schema::AttributeSchema* served = schema::findAttribute(*schema::findPrimSchema("basisCurves"), name);
    if (served && served->interpolation) return served->interpolation;
    return startsWith(name, "primvars:") ? "constant" : "vertex";
}

// UsdGeomPrimvar::ComputeFlattened: element i of the result is values[indices[i]]. Returns the
// problem when an index is out of range.
std::string flattenIndexed(usda::Value& value, const usda::Value& indices) {
    const size_t count = value.size();
    const size_t width = value.numbers.empty() ? 1 : size_t(value.tupleSize);
    std::vector<double> numbers;
    std::vector<std::string> strings;
    for (size_t i = 0; i < indices.numbers.size(); ++i) {
        const double index = indices.numbers[i];
        if (!(index >= 0 && index < double(count)))
            return "indices[" + std::to_string(i) + "] = " + std::to_string(int64_t(index)) + " is outside the " +
                   std::to_string(count) + " values";
        const size_t first = size_t(index) * width;
        if (value.numbers.empty()) strings.push_back(value.strings[size_t(index)]);
        else numbers.insert(numbers.end(), value.numbers.begin() + long(first), value.numbers.begin() + long(first + width));
    }
    value.numbers = std::move(numbers);
    value.strings = std::move(strings);
    return {};
}

// An attribute's values (its default, time samples and spline) as text, for instances to compare
// what their roots hand down; exact, as the values the plugin would be served.
void appendValuesText(const usda::Attribute& attribute, std::string& text) {
    auto appendNumber = [&](double n) {
        char number[32];
        std::snprintf(number, sizeof(number), "%.17g,", n);
        text += number;
    };
    auto append = [&](const usda::Value& value) {
        text += value.typeName + '[';
        for (double n : value.numbers) appendNumber(n);
        for (const std::string& string : value.strings) text += std::to_string(string.size()) + ':' + string;
        text += ']';
    };
    if (attribute.defaultValue) append(*attribute.defaultValue);
    for (const auto& [time, value] : attribute.timeSamples) {
        text += '@';
        appendNumber(time);
        append(value);
    }
    if (!attribute.spline) return;
    const usda::Spline& spline = *attribute.spline;
    text += "spline" + std::to_string(spline.hermite) + std::to_string(int(spline.pre.mode)) +
            std::to_string(int(spline.post.mode)) + ',';
    appendNumber(spline.pre.slope);
    appendNumber(spline.post.slope);
    if (spline.loop)
        for (double n : {spline.loop->protoStart, spline.loop->protoEnd, double(spline.loop->numPreLoops),
                         double(spline.loop->numPostLoops), spline.loop->valueOffset})
            appendNumber(n);
    for (const usda::SplineKnot& knot : spline.knots) {
        text += "knot" + std::to_string(int(knot.next)) + ',';
        for (double n : {knot.time, knot.value, knot.valueBefore(), knot.preWidth, knot.preSlope, knot.postWidth,
                         knot.postSlope})
            appendNumber(n);
    }
}

bool isIntegerType(const std::string& type) {
    return startsWith(type, "int") || startsWith(type, "uint") || type == "uchar" || type == "bool";
}

// The ABI carries integers as int32; a larger number authored in the file is bad data, not
// something to wrap around.
std::string int32RangeProblem(const usda::Value& value) {
    if (!isIntegerType(value.typeName)) return {};
    for (size_t i = 0; i < value.numbers.size(); ++i) {
        const double n = value.numbers[i];
        if (n >= -2147483648.0 && n <= 2147483647.0) continue;
        char text[64];
        std::snprintf(text, sizeof(text), "%.17g", n);
        return (value.isArray ? "element " + std::to_string(i / size_t(std::max(1, value.tupleSize))) : "value") +
               " = " + text + " does not fit in a 32-bit integer";
    }
    return {};
}

}  // namespace

const usda::Prim* UsdSceneHost::surfaceShader(const usda::Prim& material, std::string& problem) const {
    // UsdShadeMaterial::ComputeSurfaceSource: the universal render context's outputs:surface, else
    // MaterialX's outputs:mtlx:surface (what usdMtlx and MaterialX-authoring tools write), else
    // MDL's outputs:mdl:surface (Omniverse's OmniPBR, omni_pbr_surface.h).
    const usda::Attribute* surface = material.attribute("outputs:surface");
    if (!surface || !surface->connection) surface = material.attribute("outputs:mtlx:surface");
    if (!surface || !surface->connection) surface = material.attribute("outputs:mdl:surface");
    if (!surface || !surface->connection) {
        problem = "outputs:surface is not connected";
        return nullptr;
    }
    auto source = connectionSource(stage_, *surface);
    if (auto* reason = std::get_if<std::string>(&source)) {
        problem = surface->name + ": " + *reason;
        return nullptr;
    }
    const ConnectionSource& found = std::get<ConnectionSource>(source);
    if (found.attribute) {
        problem = "no shader on " + surface->name + " (it leads to the value of " + found.prim->path + "." +
                  found.property + ")";
        return nullptr;
    }
    return found.prim;
}

UsdSceneHost::UsdSceneHost(const usda::Stage& stage) : stage_(stage) {
    sceneDelegate_.sType = OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE;
    sceneDelegate_.structSize = sizeof(ObscuraSceneDelegate);
    sceneDelegate_.userData = this;
    sceneDelegate_.flags = OBSCURA_SCENE_DELEGATE_THREAD_SAFE;
    sceneDelegate_.getValue = &UsdSceneHost::getValueThunk;
    sceneDelegate_.getInterpolation = &UsdSceneHost::getInterpolationThunk;
    sceneDelegate_.sampleTransform = &UsdSceneHost::sampleTransformThunk;
}

void UsdSceneHost::warnOnce(const std::string& key, const std::string& text, const usda::SourceLocation& where,
                            bool error) {
    if (!warned_.insert(key).second) return;
    messages_.push_back({error, text, where});
    if (sink_) sink_(messages_.back());
}

std::optional<usda::SourceLocation> UsdSceneHost::locate(const PrimMessage& message) const {
    const usda::Prim* prim = stage_.find(message.primPath);
    if (!prim) return std::nullopt;
    if (!message.attribute.empty())
        if (const usda::Attribute* a = resolveAttribute(message.primPath, message.attribute)) return a->where;
    return prim->where;
}

// UsdGeomPrimvar: a primvar holds one element (of elementSize values) per constant prim, face
// (uniform), point (vertex, varying) or face-vertex (faceVarying).
std::string UsdSceneHost::primvarCountProblem(const usda::Prim& prim, const usda::Attribute& attribute,
                                              const usda::Value& value, double time) const {
    const auto interpolation = attribute.metadata.find("interpolation");
    // A TetMesh is served as a mesh of its points; its uniform and faceVarying primvars are checked
    // against its surface (convertedValue).
    const bool mesh = prim.typeName == "Mesh" || prim.typeName == "TetMesh";
    if (!mesh || interpolation == attribute.metadata.end() || interpolation->second.strings.empty())
        return {};
    const std::string& mode = interpolation->second.strings.front();
    auto countOf = [&](const char* name) -> size_t {
        const usda::Attribute* a = prim.attribute(name);
        auto v = a ? a->evaluate(time) : std::nullopt;
        return v ? v->size() : 0;
    };
    size_t expected = 0;
    std::string per;
    if (prim.typeName == "TetMesh" && (mode == "uniform" || mode == "faceVarying")) return {};
    if (mode == "constant") expected = 1, per = "constant";
    else if (mode == "uniform") expected = countOf("faceVertexCounts"), per = "uniform (one per face)";
    else if (mode == "vertex" || mode == "varying") expected = countOf("points"), per = mode + " (one per point)";
    else if (mode == "faceVarying") expected = countOf("faceVertexIndices"), per = "faceVarying (one per face-vertex)";
    else return {};
    const size_t elementSize = elementSizeOf(attribute);
    if (value.size() == expected * elementSize) return {};
    return attribute.name + " has " + std::to_string(value.size()) + " values but " + per + " interpolation needs " +
           std::to_string(expected * elementSize) + "; ignored";
}

std::map<std::string, std::string> UsdSceneHost::scan() {
    std::map<std::string, std::string> found;
    std::map<std::string, int> unsupported;
    // Instances that differ in what their roots hand down to the prototype are grouped apart.
    nativeInstancing_ = NativeInstancing(
        stage_,
        [this](const usda::Prim& instance) {
            const usda::Attribute* purpose = stage_.purposeOpinion(instance);
            const bool purposeToken = purpose && purpose->defaultValue && purpose->defaultValue->strings.size() == 1;
            std::string text =
                boundMaterial(instance).value_or("") + '\n' + (purposeToken ? purpose->defaultValue->strings.front() : "");
            for (const auto& [name, primvar] : stage_.inheritablePrimvars(instance)) {
                text += '\n' + name + '=';
                appendValuesText(*primvar, text);
                if (const usda::Attribute* indices = stage_.primAuthoring(instance, *primvar).attribute(name + ":indices"))
                    appendValuesText(*indices, text);
            }
            return text;
        },
        stage_.metadata().startTimeCode.value_or(0.0));
    for (const usda::Prim* prim : stage_.prims()) {
        // Geometry of the instances after a prototype's first is drawn by its instancer, and their
        // materials are the first's.
        if ((isInstancedGeometry(*prim) || prim->typeName == "Material") && nativeInstancing_.drawnByInstancer(*prim))
            continue;
        if (prim->typeName == "Skeleton") {
            addSkeletonGuide(*prim, found);
            continue;
        }
        auto it = kPrimTypes.find(prim->typeName);
        if (it == kPrimTypes.end()) {
            if (!kStructuralTypes.count(prim->typeName)) ++unsupported[prim->typeName];
            continue;
        }
        if (it->second == "material") {
            // UsdShade: outputs:surface connects to a UsdPreviewSurface shader, directly or through
            // NodeGraph outputs.
            std::string problem;
            const usda::Prim* shader = surfaceShader(*prim, problem);
            if (!shader) {
                const usda::Attribute* surface = prim->attribute("outputs:surface");
                warnOnce("material:" + prim->path, prim->path + ": " + problem + "; material skipped",
                         surface ? surface->where : prim->where);
                continue;
            }
            // UsdPreviewSurface is served as it is; any other surface (MaterialX node
            // definitions, or a base colour to fall back on) through its mapping.
            if (shaderId(*shader) == "UsdPreviewSurface") {
                surfaces_[prim->path] = shader;
            } else {
                mappedSurfaces_[prim->path] = MappedSurface{shader, isNetworkAnimated(stage_, *shader), std::nullopt, {}};
                mappedSurface(prim->path, stage_.metadata().startTimeCode.value_or(0.0));  // reports its problems
            }
        }
        if (isPointBased(prim->typeName)) bindSkeleton(*prim);
        if (it->second == "instancer") {
            if (const usda::Relationship* protos = prim->relationship("prototypes"))
                for (const auto& root : protos->targets)
                    if (const usda::Prim* r = stage_.find(root)) prototypeRoots_[root] = r->parent;
        }
        found[prim->path] = it->second;
    }
    for (const NativeInstancer& instancer : nativeInstancing_.instancers()) found[instancer.path] = "instancer";
    for (const auto& [type, count] : unsupported)
        warnOnce("type:" + type, "prim type '" + type + "' is not supported yet; " + std::to_string(count) +
                                     " prim(s) skipped");
    return found;
}

ObscuraStatus UsdSceneHost::populate(const ObscuraApiV1& api, ObscuraDelegate delegate) {
    for (const auto& [path, type] : scan()) {
        ObscuraStatus s = api.insertPrim(delegate, type.c_str(), path.c_str());
        if (s != OBSCURA_OK) return s;
        primTypes_[path] = type;
    }
    return OBSCURA_OK;
}

namespace {

bool sameValue(const usda::Value& a, const usda::Value& b) {
    return a.typeName == b.typeName && a.isArray == b.isArray && a.tupleSize == b.tupleSize && a.numbers == b.numbers &&
           a.strings == b.strings && a.blocked == b.blocked;
}

template <typename Map>
bool sameValues(const Map& a, const Map& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
               return x.first == y.first && sameValue(x.second, y.second);
           });
}

bool sameAttribute(const usda::Attribute& a, const usda::Attribute& b) {
    const bool defaults = a.defaultValue.has_value() == b.defaultValue.has_value() &&
                          (!a.defaultValue || sameValue(*a.defaultValue, *b.defaultValue));
    const bool splines = a.spline == b.spline || (a.spline && b.spline && *a.spline == *b.spline);
    return defaults && splines && a.typeName == b.typeName && a.connection == b.connection &&
           sameValues(a.timeSamples, b.timeSamples) &&
           sameValues(a.metadata, b.metadata);
}

// Whether two primvar readers give a prim the same value: one primvar, one fallback.
bool sameRead(const std::optional<PrimvarRead>& a, const std::optional<PrimvarRead>& b) {
    if (!a || !b) return !a && !b;
    if (a->primvar != b->primvar || !a->fallback != !b->fallback) return false;
    return !a->fallback || sameAttribute(*a->fallback, *b->fallback);
}

// Whether the attributes of `a`, `b` and of their descendants (a material's shaders) are the same.
bool sameSubtree(const usda::Prim& a, const usda::Prim& b) {
    if (a.attributes.size() != b.attributes.size() || a.children.size() != b.children.size() || a.typeName != b.typeName)
        return false;
    for (const auto& [name, attribute] : a.attributes) {
        const usda::Attribute* other = b.attribute(name);
        if (!other || !sameAttribute(attribute, *other)) return false;
    }
    for (size_t i = 0; i < a.children.size(); ++i)
        if (a.children[i]->name != b.children[i]->name || !sameSubtree(*a.children[i], *b.children[i])) return false;
    return true;
}

}  // namespace

ObscuraDirtyBits UsdSceneHost::changes(const std::string& type, const usda::Prim& prim, const UsdSceneHost& previous, const usda::Prim& before,
                                       double time) const {
    ObscuraDirtyBits bits = 0;
    std::set<std::string> names;
    for (const auto& [name, a] : prim.attributes) names.insert(name);
    for (const auto& [name, a] : before.attributes) names.insert(name);
    for (const std::string& name : names) {
        const usda::Attribute* a = prim.attribute(name);
        const usda::Attribute* b = before.attribute(name);
        if (!a || !b || !sameAttribute(*a, *b)) bits |= attributeDirtyBit(prim, type, name);
    }
    std::set<std::string> relationships;
    for (const auto& [name, r] : prim.relationships) relationships.insert(name);
    for (const auto& [name, r] : before.relationships) relationships.insert(name);
    for (const std::string& name : relationships) {
        const usda::Relationship* a = prim.relationship(name);
        const usda::Relationship* b = before.relationship(name);
        if (a && b && a->targets == b->targets) continue;
        bits |= name == "prototypes" ? OBSCURA_DIRTY_ALL : name == "material:binding" ? OBSCURA_DIRTY_MATERIAL_ID
                                                                                      : OBSCURA_DIRTY_PARAMS;
    }
    // What the prim inherits from its ancestors: transform, visibility, purpose, material binding,
    // constant primvars.
    const usda::Stage& old = previous.stage_;
    if (stage_.transformSampleTimes(prim) != old.transformSampleTimes(before) ||
        stage_.worldTransform(prim, time) != old.worldTransform(before, time))
        bits |= dirtyBitFor(type, "transform");
    if (stage_.isVisible(prim, time) != old.isVisible(before, time)) bits |= dirtyBitFor(type, "visibility");
    const auto primvars = stage_.inheritablePrimvars(*prim.parent), primvarsBefore = old.inheritablePrimvars(*before.parent);
    for (const auto& [name, attribute] : primvars) {
        const auto it = primvarsBefore.find(name);
        if (it == primvarsBefore.end() || !sameAttribute(*attribute, *it->second)) bits |= dirtyBitFor(type, name);
    }
    for (const auto& [name, attribute] : primvarsBefore)
        if (!primvars.count(name)) bits |= dirtyBitFor(type, name);
    const usda::Attribute* purpose = stage_.purposeOpinion(prim);
    const usda::Attribute* purposeBefore = old.purposeOpinion(before);
    if ((purpose == nullptr) != (purposeBefore == nullptr) || (purpose && !sameAttribute(*purpose, *purposeBefore)))
        bits |= dirtyBitFor(type, "purpose");
    if (boundMaterial(prim) != previous.boundMaterial(before)) bits |= OBSCURA_DIRTY_MATERIAL_ID;
    // The primvars served as displayColor and displayOpacity follow the bound material's readers.
    for (const auto& [served, read] : kServedReads)
        if (!sameRead(boundPrimvarRead(prim, read.input), previous.boundPrimvarRead(before, read.input)))
            bits |= dirtyBitFor(type, served);
    // A mesh's material subsets are its children: their faces are its topology, their bindings its own.
    if (prim.typeName == "Mesh" || before.typeName == "Mesh") {
        const MaterialBindSubsets subsets = bindSubsets(prim, time);
        const MaterialBindSubsets subsetsBefore = previous.bindSubsets(before, time);
        if (subsets.faceCounts != subsetsBefore.faceCounts || subsets.faceIndices != subsetsBefore.faceIndices ||
            subsets.paths != subsetsBefore.paths)
            bits |= dirtyBitFor(type, "materialSubsets:faceIndices");
        if (subsets.materials != subsetsBefore.materials) bits |= dirtyBitFor(type, "materialSubsets:materials");
    }
    // A material's values are its surface shader's and its textures': any change in its network.
    auto surface = surfaces_.find(prim.path);
    auto surfaceBefore = previous.surfaces_.find(before.path);
    if (surface != surfaces_.end() && surfaceBefore != previous.surfaces_.end() &&
        (!sameSubtree(prim, before) || !sameSubtree(*surface->second, *surfaceBefore->second)))
        bits |= OBSCURA_DIRTY_PARAMS;
    return bits;
}

ObscuraStatus UsdSceneHost::adoptChanges(const UsdSceneHost& previous, const ObscuraApiV1& api,
                                         ObscuraDelegate delegate, double time, size_t& touched) {
    touched = 0;
    const std::map<std::string, std::string> now = scan();
    for (const auto& [path, type] : previous.primTypes_) {
        auto it = now.find(path);
        if (it != now.end() && it->second == type) continue;
        ObscuraStatus s = api.removePrim(delegate, path.c_str());
        if (s != OBSCURA_OK) return s;
        ++touched;
    }
    for (const auto& [path, type] : now) {
        auto it = previous.primTypes_.find(path);
        ObscuraStatus s = OBSCURA_OK;
        const NativeInstancer* instancer = nativeInstancing_.instancer(path);
        if (it == previous.primTypes_.end() || it->second != type) {
            s = api.insertPrim(delegate, type.c_str(), path.c_str());
            ++touched;
        } else if (instancer) {
            const NativeInstancer* before = previous.nativeInstancing_.instancer(path);
            if (!before || !samePlacements(*instancer, stage_, *before, previous.stage_, time)) {
                s = api.markDirty(delegate, path.c_str(), OBSCURA_DIRTY_ALL);
                ++touched;
            }
        } else if (ObscuraDirtyBits bits = changes(type, *stage_.find(path), previous, *previous.stage_.find(path), time)) {
            s = api.markDirty(delegate, path.c_str(), bits);
            ++touched;
        }
        if (s != OBSCURA_OK) return s;
        primTypes_[path] = type;
    }
    return OBSCURA_OK;
}

ObscuraDirtyBits UsdSceneHost::animatedValueBits(const std::string& path, const std::string& type,
                                                 const usda::Prim& prim) const {
    ObscuraDirtyBits bits = 0;
    // A mapped (MaterialX) surface is mapped again at each frame's time; what it serves changes
    // when its network is animated, under the schema's bits of the values it maps to.
    if (const auto mapped = mappedSurfaces_.find(path); mapped != mappedSurfaces_.end()) {
        if (mapped->second.animated)
            for (const auto& [name, value] : mapped->second.mapping.values) bits |= dirtyBitFor(type, name);
        return bits;
    }
    const usda::Prim* valuesFrom = type == "material" ? surfaces_.at(path) : &prim;
    if (type != "material")
        for (const auto& [name, attr] : stage_.inheritablePrimvars(*prim.parent))
            if (attr->isAnimated()) bits |= dirtyBitFor(type, name);
    for (const auto& [name, attr] : valuesFrom->attributes) {
        // A surface input takes its value from the interface input it connects to.
        const usda::Attribute* source = type == "material" && attr.connection ? valueProducingAttribute(stage_, attr) : &attr;
        if (source && source->isAnimated()) bits |= attributeDirtyBit(prim, type, name);
        // A texture's inputs are served as the material's obscura:<input>:<field>.
        if (auto texture = type == "material" ? textureConnection(stage_, attr) : std::nullopt)
            for (const auto& [textureInput, textureAttr] : texture->texture->attributes)
                if (textureAttr.isAnimated() && startsWith(name, "inputs:") && startsWith(textureInput, "inputs:"))
                    bits |= dirtyBitFor(type, "obscura:" + name.substr(7) + ":" + textureInput.substr(7));
    }
    return bits;
}

ObscuraStatus UsdSceneHost::markTimeVarying(const ObscuraApiV1& api, ObscuraDelegate delegate) {
    for (const auto& [path, type] : primTypes_) {
        if (const NativeInstancer* instancer = nativeInstancing_.instancer(path)) {
            ObscuraDirtyBits bits = 0;
            if (nativeInstancing_.hasAnimatedTransforms(*instancer, stage_)) bits |= dirtyBitFor(type, "positions");
            if (nativeInstancing_.hasAnimatedVisibility(*instancer, stage_)) bits |= dirtyBitFor(type, "invisibleIds");
            if (ObscuraStatus s = bits ? api.markDirty(delegate, path.c_str(), bits) : OBSCURA_OK; s != OBSCURA_OK) return s;
            continue;
        }
        const usda::Prim* prim = stage_.find(path);
        ObscuraDirtyBits bits = 0;
        if (!stage_.transformSampleTimes(*prim).empty()) bits |= dirtyBitFor(type, "transform");
        // Visibility is inherited: an ancestor's samples change the prim's computed visibility.
        if (stage_.hasAnimatedVisibility(*prim)) bits |= dirtyBitFor(type, "visibility");
        if (auto skin = skinnings_.find(path); skin != skinnings_.end() && usda::isSkinningAnimated(stage_, skin->second))
            bits |= dirtyBitFor(type, "points") | dirtyBitFor(type, "normals");
        if (auto guide = skeletonGuides_.find(path); guide != skeletonGuides_.end() && guide->second.animation &&
                                                     usda::isSkinningAnimated(stage_, guide->second))
            bits |= dirtyBitFor(type, "points");
        bits |= animatedValueBits(path, type, *prim);
        if (prim->typeName == "Mesh" && bindSubsets(*prim, 0.0).animated)
            bits |= dirtyBitFor(type, "materialSubsets:faceIndices");
        if (bits) {
            ObscuraStatus s = api.markDirty(delegate, path.c_str(), bits);
            if (s != OBSCURA_OK) return s;
        }
    }
    return OBSCURA_OK;
}

std::string aovBufferFormat(const std::string& aov) {
    return aov == "color"                            ? "float32Vec4"
           : aov == "depth"                          ? "float32"
           : aov == "primId" || aov == "instanceId" ? "int32"
           : aov == "display"                        ? "unorm8Vec4"
                                                     : "float32Vec3";
}

std::string UsdSceneHost::addRenderBuffer(const ObscuraApiV1& api, ObscuraDelegate delegate, const std::string& aov,
                                          int width, int height) {
    std::string path = "/Render/Buffers/" + aov;
    std::string format = aovBufferFormat(aov);
    bool exists = renderBuffers_.count(path) > 0;
    renderBuffers_[path] = {width, height, format};
    if (!exists) api.insertPrim(delegate, "renderBuffer", path.c_str());
    else api.markDirty(delegate, path.c_str(), OBSCURA_DIRTY_PARAMS);
    return path;
}

std::string UsdSceneHost::defaultCamera() const {
    for (const usda::Prim* prim : stage_.prims())
        if (prim->typeName == "Camera") return prim->path;
    return {};
}

SceneBounds UsdSceneHost::bounds(double time) {
    // XXX: only point-based prims (Mesh, BasisCurves, Points, TetMesh, and NurbsCurves and
    // HermiteCurves by their Bezier control points, which hold the curves) are framed, by their
    // points; implicit gprims (Cube, Sphere...) are left out of the bounds.
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const usda::Prim* prim : stage_.prims()) {
        if (!isPointBased(prim->typeName) || pointInstancerSpace(*prim)) continue;
        const usda::Attribute* points = prim->attribute("points");
        auto value = points ? points->evaluate(time) : std::nullopt;
        if (!value || value->tupleSize != 3) continue;
        if (auto skin = skinnings_.find(prim->path); skin != skinnings_.end())
            applySkinning(*prim, skin->second, *points, *value, time);
        if (const ConvertedPrim* converted = isConvertedCurves(prim->typeName) ? convertedForm(*prim, time) : nullptr) {
            const auto* bezier = std::get_if<usda::BezierCurves>(&converted->form);
            if (!bezier) continue;
            value->numbers = bezierControlPoints(*prim, *bezier, *value, time);
        }
        auto m = stage_.worldTransform(*prim, time);
        for (size_t i = 0; i + 2 < value->numbers.size(); i += 3) {
            const double* p = &value->numbers[i];
            for (int c = 0; c < 3; ++c) {
                double w = p[0] * m[size_t(c)] + p[1] * m[size_t(4 + c)] + p[2] * m[size_t(8 + c)] + m[size_t(12 + c)];
                if (!std::isfinite(w)) continue;
                lo[c] = std::min(lo[c], w);
                hi[c] = std::max(hi[c], w);
            }
        }
    }
    SceneBounds b;
    double radius = 0;
    for (int c = 0; c < 3; ++c) {
        if (lo[c] > hi[c]) lo[c] = hi[c] = 0;  // nothing to frame: look at the origin
        b.centre[size_t(c)] = 0.5 * (lo[c] + hi[c]);
        radius += 0.25 * (hi[c] - lo[c]) * (hi[c] - lo[c]);
    }
    b.radius = std::max(std::sqrt(radius), 1e-3);
    return b;
}

std::string UsdSceneHost::instancerOf(const std::string& path) const {
    for (const auto& [instancer, type] : primTypes_) {
        if (type != "instancer") continue;
        const usda::Prim* prim = stage_.find(instancer);
        const usda::Relationship* protos = prim ? prim->relationship("prototypes") : nullptr;
        if (!protos) continue;
        for (const auto& root : protos->targets)
            if (path == root || path.rfind(root + "/", 0) == 0) return instancer;
    }
    return {};
}

std::string UsdSceneHost::instanceProxyPath(const std::string& path, int32_t instanceId) const {
    const usda::Prim* prim = stage_.find(path);
    const NativeInstancer* instancer = prim ? nativeInstancing_.prototypeHolding(*prim) : nullptr;
    if (!instancer || instanceId < 0 || size_t(instanceId) >= instancer->instances.size()) return {};
    return instancer->instances[size_t(instanceId)]->path + path.substr(instancer->prototype->path.size());
}

std::string UsdSceneHost::addFramingCamera(const ObscuraApiV1& api, ObscuraDelegate delegate, double time) {
    const SceneBounds b = bounds(time);
    const double* centre = b.centre.data();
    const double radius = b.radius;
    // The camera schema's default lens; the bounding sphere fits the narrower (vertical) field of view.
    double halfFov = std::atan(schema::defaultNumber("camera", "verticalAperture") / 2.0 /
                               schema::defaultNumber("camera", "focalLength"));
    double distance = radius / std::sin(halfFov);
    FramingCamera cam{"/ObscuraFramingCamera", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, centre[0], centre[1], centre[2] + distance, 1},
                      {float(std::max(distance - 2.0 * radius, distance * 1e-3)), float(distance + 2.0 * radius)}};
    bool exists = framingCamera_.has_value();
    framingCamera_ = cam;
    if (!exists) api.insertPrim(delegate, "camera", cam.path.c_str());
    else api.markDirty(delegate, cam.path.c_str(), OBSCURA_DIRTY_ALL);
    return cam.path;
}

const usda::Attribute* UsdSceneHost::resolveAttribute(const std::string& path, const std::string& attribute) const {
    auto surface = surfaces_.find(path);
    if (surface != surfaces_.end()) return surface->second->attribute(attribute);
    const usda::Prim* prim = stage_.find(path);
    if (!prim) return nullptr;
    // A mesh's texture coordinates are the primvar its material's textures read (the varname of
    // their UsdPrimvarReader_float2), served under the delegate's one name.
    if (attribute == "primvars:st" && prim->typeName == "Mesh") {
        auto material = boundMaterial(*prim);
        auto bound = material ? surfaces_.find(*material) : surfaces_.end();
        std::string primvar = bound != surfaces_.end() ? texturePrimvar(stage_, *bound->second) : "st";
        if (auto mapped = material ? mappedSurfaces_.find(*material) : mappedSurfaces_.end(); mapped != mappedSurfaces_.end())
            primvar = mapped->second.mapping.stPrimvar;
        return stage_.primvar(*prim, "primvars:" + primvar);
    }
    // A material whose diffuseColor (opacity) reads a primvar gets it as the prim's displayColor
    // (displayOpacity), or the reader's fallback where the prim has none (unauthored: zero, the
    // reader's default).
    if (const auto served = kServedReads.find(attribute); served != kServedReads.end())
        if (auto read = boundPrimvarRead(*prim, served->second.input)) {
            const usda::Attribute* primvar = stage_.primvar(*prim, "primvars:" + read->primvar);
            // An instancer without the primvar leaves its prototypes their own.
            if (prim->typeName == "PointInstancer") return primvar;
            return primvar ? primvar : read->fallback ? read->fallback : &served->second.zero;
        }
    // UsdGeomPointBased: primvars:normals, when authored, takes precedence over normals.
    if (attribute == "normals")
        if (const usda::Attribute* primvar = prim->attribute("primvars:normals")) return primvar;
    // Constant primvars are inherited down namespace (an instance root's among them).
    if (startsWith(attribute, "primvars:"))
        if (const usda::Attribute* a = stage_.primvar(*prim, attribute)) return a;
    if (const usda::Attribute* a = prim->attribute(attribute)) return a;
    // UsdLux before 21.02 named light inputs without the "inputs:" prefix.
    if (startsWith(attribute, "inputs:")) return prim->attribute(attribute.substr(7));
    return nullptr;
}

ObscuraStatus UsdSceneHost::fill(const usda::Value& v, ObscuraValue* out) {
    ReturnedValues& storage = returned();
    out->isArray = v.isArray ? 1 : 0;
    out->count = v.size();
    const std::string& t = v.typeName;
    if (!v.strings.empty() || t == "token" || t == "string" || t == "asset") {
        storage.strings = v.strings;
        storage.stringPointers.clear();
        for (const auto& s : storage.strings) storage.stringPointers.push_back(s.c_str());
        out->type = OBSCURA_VALUE_TOKEN;
        out->data = storage.stringPointers.data();
        return OBSCURA_OK;
    }
    bool integer = startsWith(t, "int") || startsWith(t, "uint") || t == "uchar";
    if (t == "bool" || (integer && v.tupleSize == 1)) {
        storage.ints.assign(v.numbers.begin(), v.numbers.end());
        std::transform(v.numbers.begin(), v.numbers.end(), storage.ints.begin(), [](double d) { return int32_t(d); });
        out->type = t == "bool" ? OBSCURA_VALUE_BOOL : OBSCURA_VALUE_INT;
        out->data = storage.ints.data();
        return OBSCURA_OK;
    }
    if (integer && v.tupleSize == 2) {
        storage.ints.resize(v.numbers.size());
        std::transform(v.numbers.begin(), v.numbers.end(), storage.ints.begin(), [](double d) { return int32_t(d); });
        out->type = OBSCURA_VALUE_INT2;
        out->data = storage.ints.data();
        return OBSCURA_OK;
    }
    if (v.tupleSize == 16 || ((t == "double" || t == "timecode") && v.tupleSize == 1)) {
        storage.doubles = v.numbers;
        out->type = v.tupleSize == 16 ? OBSCURA_VALUE_MATRIX4D : OBSCURA_VALUE_DOUBLE;
        out->data = storage.doubles.data();
        return OBSCURA_OK;
    }
    storage.floats.resize(v.numbers.size());
    std::transform(v.numbers.begin(), v.numbers.end(), storage.floats.begin(), [](double d) { return float(d); });
    switch (v.tupleSize) {
        case 1: out->type = OBSCURA_VALUE_FLOAT; break;
        case 2: out->type = OBSCURA_VALUE_FLOAT2; break;
        case 3: out->type = OBSCURA_VALUE_FLOAT3; break;
        case 4: out->type = OBSCURA_VALUE_FLOAT4; break;
        default: return OBSCURA_ERROR_INVALID_ARGUMENT;
    }
    out->data = storage.floats.data();
    return OBSCURA_OK;
}

ObscuraStatus UsdSceneHost::fillToken(const char* token, ObscuraValue* out) {
    usda::Value value;
    value.typeName = "token";
    value.strings = {token};
    return fill(value, out);
}

ObscuraStatus UsdSceneHost::getValue(const std::string& path, const std::string& attribute, double time,
                                     ObscuraValue* out) {
    ReturnedValues& storage = returned();
    auto rb = renderBuffers_.find(path);
    if (rb != renderBuffers_.end()) {
        if (attribute == "dimensions") {
            storage.ints = {rb->second.width, rb->second.height};
            *out = {OBSCURA_VALUE_INT2, 0, 1, storage.ints.data()};
            return OBSCURA_OK;
        }
        if (attribute == "format") {
            storage.strings = {rb->second.format};
            storage.stringPointers = {storage.strings[0].c_str()};
            *out = {OBSCURA_VALUE_TOKEN, 0, 1, storage.stringPointers.data()};
            return OBSCURA_OK;
        }
        return OBSCURA_ERROR_NOT_FOUND;
    }
    if (framingCamera_ && path == framingCamera_->path) {
        if (attribute != "clippingRange") return OBSCURA_ERROR_NOT_FOUND;  // schema defaults
        storage.floats.assign(framingCamera_->clippingRange, framingCamera_->clippingRange + 2);
        *out = {OBSCURA_VALUE_FLOAT2, 0, 1, storage.floats.data()};
        return OBSCURA_OK;
    }
    if (const NativeInstancer* instancer = nativeInstancing_.instancer(path))
        return getNativeInstancerValue(*instancer, attribute, time, out);
    const usda::Prim* prim = stage_.find(path);
    if (!prim) return OBSCURA_ERROR_NOT_FOUND;
    if (auto guide = skeletonGuides_.find(path); guide != skeletonGuides_.end())
        if (auto served = skeletonGuideValue(guide->second, attribute, time, out)) return *served;
    if (auto served = convertedValue(*prim, attribute, time, out)) return *served;
    if (attribute == "purpose") return computedPurpose(*prim, out);
    if (attribute == "visibility") {
        storage.strings = {stage_.isVisible(*prim, time) ? "inherited" : "invisible"};
        storage.stringPointers = {storage.strings[0].c_str()};
        *out = {OBSCURA_VALUE_TOKEN, 0, 1, storage.stringPointers.data()};
        return OBSCURA_OK;
    }
    if (attribute == "prototypes") {
        const usda::Relationship* rel = prim->relationship("prototypes");
        if (!rel) return OBSCURA_ERROR_NOT_FOUND;
        storage.strings = rel->targets;
        storage.stringPointers.clear();
        for (const auto& t : storage.strings) storage.stringPointers.push_back(t.c_str());
        *out = {OBSCURA_VALUE_PATH, 1, storage.strings.size(), storage.stringPointers.data()};
        return OBSCURA_OK;
    }
    if (attribute == "obscura:clipVolume") {
        const usda::Relationship* rel = prim->relationship(attribute);
        if (!rel || rel->targets.empty()) return OBSCURA_ERROR_NOT_FOUND;
        storage.strings = {rel->targets.front()};
        storage.stringPointers = {storage.strings[0].c_str()};
        *out = {OBSCURA_VALUE_PATH, 0, 1, storage.stringPointers.data()};
        return OBSCURA_OK;
    }
    if (startsWith(attribute, "materialSubsets:") && prim->typeName == "Mesh") {
        const MaterialBindSubsets subsets = bindSubsets(*prim, time);
        if (subsets.empty()) return OBSCURA_ERROR_NOT_FOUND;
        if (attribute == "materialSubsets:faceCounts" || attribute == "materialSubsets:faceIndices") {
            storage.ints = attribute == "materialSubsets:faceCounts" ? subsets.faceCounts : subsets.faceIndices;
            *out = {OBSCURA_VALUE_INT, 1, storage.ints.size(), storage.ints.data()};
            return OBSCURA_OK;
        }
        if (attribute != "materialSubsets:materials" && attribute != "materialSubsets:paths") return OBSCURA_ERROR_NOT_FOUND;
        storage.strings = attribute == "materialSubsets:materials" ? subsets.materials : subsets.paths;
        storage.stringPointers.clear();
        for (const auto& t : storage.strings) storage.stringPointers.push_back(t.c_str());
        *out = {OBSCURA_VALUE_PATH, 1, storage.strings.size(), storage.stringPointers.data()};
        return OBSCURA_OK;
    }
    if (attribute == "material:binding") {
        auto material = boundMaterial(*prim);
        if (!material) return OBSCURA_ERROR_NOT_FOUND;
        storage.strings = {*material};
        storage.stringPointers = {storage.strings[0].c_str()};
        *out = {OBSCURA_VALUE_PATH, 0, 1, storage.stringPointers.data()};
        return OBSCURA_OK;
    }
    if (const MaterialXMapping* mapped = mappedSurface(path, time)) {
        const auto value = mapped->values.find(attribute);
        return value == mapped->values.end() ? OBSCURA_ERROR_NOT_FOUND : fill(value->second, out);
    }
    auto surface = surfaces_.find(path);
    if (surface != surfaces_.end() && (attribute == "obscura:diffuseColor:primvar" || attribute == "obscura:opacity:primvar")) {
        const std::string input = attribute == "obscura:opacity:primvar" ? "inputs:opacity" : "inputs:diffuseColor";
        auto read = primvarRead(stage_, *surface->second, input);
        if (!read) return OBSCURA_ERROR_NOT_FOUND;
        usda::Value name;
        name.typeName = "token";
        name.strings = std::vector<std::string>{read->primvar};
        return fill(name, out);
    }
    // The primvar a reader reads replaces diffuseColor: it scales the vertex colour by 1.
    if (surface != surfaces_.end() && attribute == "inputs:diffuseColor" &&
        primvarRead(stage_, *surface->second, attribute)) {
        usda::Value one;
        one.typeName = "float3";
        one.tupleSize = 3;
        one.numbers = std::vector<double>{1.0, 1.0, 1.0};
        return fill(one, out);
    }
    if (surface != surfaces_.end() && startsWith(attribute, "obscura:")) {
        std::optional<MaterialProblem> problem;
        auto texture = flattenedTextureAttribute(stage_, *surface->second, attribute, time, &problem);
        if (problem)
            warnOnce("shading:" + problem->message, path + ": " + problem->message, problem->where);
        return texture ? fill(*texture, out) : OBSCURA_ERROR_NOT_FOUND;
    }
    usda::Value value;
    if (ObscuraStatus status = authoredValue(*prim, attribute, time, value); status != OBSCURA_OK) return status;
    return fill(value, out);
}

ObscuraStatus UsdSceneHost::authoredValue(const usda::Prim& prim, const std::string& attribute, double time,
                                          usda::Value& out) {
    const std::string& path = prim.path;
    const usda::Attribute* a = resolveAttribute(path, attribute);
    if (!a) return OBSCURA_ERROR_NOT_FOUND;
    // Textures on the inputs the delegate textures arrive as obscura:<input>:* (getValue); an input
    // connected to an interface input (a Material's or NodeGraph's) takes its value there.
    bool textured = surfaces_.count(path) && isTexturableInput(attribute) && textureConnection(stage_, *a);
    // A diffuseColor or opacity that reads a primvar is served as obscura:<input>:primvar.
    bool readsPrimvar = surfaces_.count(path) && primvarRead(stage_, *surfaces_.at(path), attribute);
    if (a->connection && !textured && !readsPrimvar) {
        if (const usda::Attribute* source = valueProducingAttribute(stage_, *a)) {
            a = source;
        } else {
            auto reason = connectionSource(stage_, *a);
            auto* shader = std::get_if<ConnectionSource>(&reason);
            warnOnce("connection:" + path + attribute,
                     path + ": " + attribute +
                         (shader ? " is connected to " + shader->prim->path + "." + shader->property +
                                       ", a shading network which is not supported yet"
                                 : ": " + std::get<std::string>(reason)) +
                         "; its authored value or the default is used",
                     a->where);
        }
    }
    auto value = a->evaluate(time);
    // A declared but valueless attribute is unauthored; an empty array is an authored value.
    if (!value || (value->empty() && !value->isArray)) return OBSCURA_ERROR_NOT_FOUND;
    // A primvar reader's fallback served as displayColor or displayOpacity: one constant element.
    if (kServedReads.count(attribute)) value->isArray = true;
    // Hosts resolve asset paths (a dome's inputs:texture:file).
    if (value->typeName == "asset")
        for (auto& asset : value->strings.edit())
            if (!asset.empty()) asset = resolveAssetPath(asset, *a);
    const usda::Attribute* indices =
        startsWith(a->name, "primvars:") ? stage_.primAuthoring(prim, *a).attribute(a->name + ":indices") : nullptr;
    if (auto indexValues = indices ? indices->evaluate(time) : std::nullopt) {
        if (std::string problem = flattenIndexed(*value, *indexValues); !problem.empty()) {
            warnOnce("indices:" + path + a->name, path + ": " + a->name + ":" + problem + " of " + a->name,
                     indices->where, true);
            return OBSCURA_ERROR_INVALID_ARGUMENT;
        }
    }
    if (std::string problem = int32RangeProblem(*value); !problem.empty()) {
        warnOnce("range:" + path + a->name, path + ": " + a->name + ": " + problem, a->where, true);
        return OBSCURA_ERROR_INVALID_ARGUMENT;
    }
    if (startsWith(a->name, "primvars:") || a->name == "normals") {
        if (std::string problem = primvarCountProblem(prim, *a, *value, time); !problem.empty()) {
            warnOnce("count:" + path + a->name, path + ": " + problem, a->where);
            return OBSCURA_ERROR_NOT_FOUND;
        }
    }
    if (auto skin = skinnings_.find(path); skin != skinnings_.end() && (attribute == "points" || attribute == "normals"))
        applySkinning(prim, skin->second, *a, *value, time);
    out = std::move(*value);
    return OBSCURA_OK;
}

const MaterialXMapping* UsdSceneHost::mappedSurface(const std::string& material, double time) {
    const auto it = mappedSurfaces_.find(material);
    if (it == mappedSurfaces_.end()) return nullptr;
    MappedSurface& mapped = it->second;
    if (mapped.time != time) {
        mapped.mapping = isOmniPbrShader(*mapped.shader) ? mapOmniPbrSurface(stage_, *mapped.shader, time)
                                                          : mapMaterialXSurface(stage_, *mapped.shader, time);
        mapped.time = time;
        for (const MaterialProblem& problem : mapped.mapping.problems)
            // Once per node as authored: materials that share a document share its nodes.
            warnOnce("mapped:" + problem.where.file + ":" + std::to_string(problem.where.line) + ":" +
                         std::to_string(problem.where.column),
                     material + ": " + problem.message, problem.where);
    }
    return &mapped.mapping;
}

void UsdSceneHost::addSkeletonGuide(const usda::Prim& skeleton, std::map<std::string, std::string>& found) {
    auto resolved = usda::resolveSkeleton(stage_, skeleton);
    if (auto* problem = std::get_if<usda::SkinningProblem>(&resolved)) {
        warnOnce("skeleton:" + skeleton.path, skeleton.path + ": " + problem->message + "; its bones are not drawn",
                 problem->where);
        return;
    }
    usda::Skinning& bones = std::get<usda::Skinning>(resolved);
    if (usda::boneCount(bones) == 0) return;  // a lone joint has nothing to join
    skeletonGuides_.emplace(skeleton.path, std::move(bones));
    found[skeleton.path] = "mesh";
}

std::optional<ObscuraStatus> UsdSceneHost::skeletonGuideValue(const usda::Skinning& skeleton, const std::string& attribute,
                                                              double time, ObscuraValue* out) {
    if (attribute == "purpose") return fillToken("guide", out);
    if (attribute == "subdivisionScheme") return fillToken("none", out);  // bones are flat-faced
    if (attribute != "points" && attribute != "faceVertexCounts" && attribute != "faceVertexIndices") return std::nullopt;
    std::string problem;
    const usda::BoneMesh bones = usda::boneMesh(skeleton, time, &problem);
    if (!problem.empty())
        warnOnce("pose:" + skeleton.animation->path, skeleton.skeleton->path + ": " + problem, skeleton.animation->where);
    return fill(attribute == "points"             ? bones.points
                : attribute == "faceVertexCounts" ? bones.faceVertexCounts
                                                  : bones.faceVertexIndices,
                out);
}

const UsdSceneHost::ConvertedPrim* UsdSceneHost::convertedForm(const usda::Prim& prim, double time) {
    const bool tets = prim.typeName == "TetMesh";
    if (!tets && !isConvertedCurves(prim.typeName)) return nullptr;
    auto it = converted_.find(prim.path);
    if (it != converted_.end() && it->second.time == time) return &it->second;
    ConvertedPrim converted{time, usda::AttributeProblem{}};
    if (tets) {
        auto surface = usda::tetMeshSurface(prim, time);
        if (auto* faces = std::get_if<std::vector<int>>(&surface)) converted.form = std::move(*faces);
        else converted.form = std::get<usda::AttributeProblem>(surface);
    } else {
        auto curves = prim.typeName == "NurbsCurves" ? usda::nurbsCurvesAsBezier(prim, time)
                                                     : usda::hermiteCurvesAsBezier(prim, time);
        if (auto* bezier = std::get_if<usda::BezierCurves>(&curves)) converted.form = std::move(*bezier);
        else converted.form = std::get<usda::AttributeProblem>(curves);
    }
    if (auto* problem = std::get_if<usda::AttributeProblem>(&converted.form))
        warnOnce("converted:" + prim.path, prim.path + ": " + problem->message + "; not drawn",
                 usda::whereAuthored(prim, problem->attribute));
    return &(converted_[prim.path] = std::move(converted));
}

std::vector<double> UsdSceneHost::bezierControlPoints(const usda::Prim& prim, const usda::BezierCurves& curves,
                                                      const usda::Value& points, double time) const {
    std::vector<double> input = points.numbers;
    // A Hermite curve's inner control points lie along its tangents (usda/hermite_curves.h).
    // XXX: skinning moves the points but not the tangents.
    if (curves.positions.inputCount > curves.vertex.inputCount) {
        const usda::Attribute* tangents = prim.attribute("tangents");
        if (auto value = tangents ? tangents->evaluate(time) : std::nullopt)
            input.insert(input.end(), value->numbers.begin(), value->numbers.end());
    }
    if (input.size() != curves.positions.inputCount * 3) return {};  // what was validated at another time
    return curves.positions.apply(input, 3);
}

std::optional<ObscuraStatus> UsdSceneHost::convertedValue(const usda::Prim& prim, const std::string& attribute,
                                                          double time, ObscuraValue* out) {
    ReturnedValues& storage = returned();
    const bool curves = isConvertedCurves(prim.typeName);
    if (!curves && prim.typeName != "TetMesh") return std::nullopt;
    auto ints = [&](std::vector<int32_t> values) {
        storage.ints = std::move(values);
        *out = {OBSCURA_VALUE_INT, 1, storage.ints.size(), storage.ints.data()};
        return OBSCURA_OK;
    };
    if (curves && attribute == "type") return fillToken("cubic", out);
    if (curves && attribute == "basis") return fillToken("bezier", out);
    if (curves && attribute == "wrap") return fillToken("nonperiodic", out);
    if (!curves && attribute == "subdivisionScheme") return fillToken("none", out);  // tets are flat-faced
    const bool topology = curves ? attribute == "curveVertexCounts"
                                 : attribute == "faceVertexCounts" || attribute == "faceVertexIndices";
    if (!topology && !isPerElement(attribute)) return std::nullopt;
    const ConvertedPrim& converted = *convertedForm(prim, time);
    if (std::holds_alternative<usda::AttributeProblem>(converted.form)) {
        if (topology) return ints({});
        if (attribute != "points") return OBSCURA_ERROR_NOT_FOUND;
        storage.floats.clear();
        *out = {OBSCURA_VALUE_FLOAT3, 1, 0, storage.floats.data()};
        return OBSCURA_OK;
    }
    if (const auto* faces = std::get_if<std::vector<int>>(&converted.form)) {
        if (attribute == "faceVertexCounts") return ints(std::vector<int32_t>(faces->size() / 3, 3));
        if (attribute == "faceVertexIndices") return ints(*faces);
        const usda::Attribute* a = resolveAttribute(prim.path, attribute);
        const std::string interpolation = a ? authoredInterpolation(*a) : "";
        // The points, constant and vertex primvars are the tets' own.
        if (interpolation != "uniform" && interpolation != "faceVarying") return std::nullopt;
        usda::Value value;
        if (ObscuraStatus status = authoredValue(prim, attribute, time, value); status != OBSCURA_OK) return status;
        if (std::string problem = usda::tetSurfacePrimvarProblem(faces->size() / 3, value.size(), interpolation,
                                                                 elementSizeOf(*a));
            !problem.empty()) {
            warnOnce("count:" + prim.path + a->name, prim.path + ": " + a->name + " has " + problem + "; ignored", a->where);
            return OBSCURA_ERROR_NOT_FOUND;
        }
        return fill(value, out);
    }
    const usda::BezierCurves& bezier = std::get<usda::BezierCurves>(converted.form);
    if (attribute == "curveVertexCounts") return ints(std::vector<int32_t>(bezier.curveVertexCounts.begin(), bezier.curveVertexCounts.end()));
    usda::Value value;
    if (ObscuraStatus status = authoredValue(prim, attribute, time, value); status != OBSCURA_OK) return status;
    if (attribute == "points") {
        value.numbers = bezierControlPoints(prim, bezier, value, time);
        return fill(value, out);
    }
    const usda::Attribute* a = resolveAttribute(prim.path, attribute);
    auto served = usda::convertCurvesPrimvar(bezier, value, curvesInterpolation(*a, attribute), elementSizeOf(*a));
    if (auto* problem = std::get_if<std::string>(&served)) {
        warnOnce("count:" + prim.path + a->name, prim.path + ": " + a->name + " has " + *problem + "; ignored", a->where);
        return OBSCURA_ERROR_NOT_FOUND;
    }
    return fill(std::get<usda::Value>(served), out);
}

void UsdSceneHost::bindSkeleton(const usda::Prim& prim) {
    auto skinning = usda::resolveSkinning(stage_, prim);
    if (!skinning) return;
    if (auto* problem = std::get_if<usda::SkinningProblem>(&*skinning)) {
        warnOnce("skel:" + prim.path, prim.path + ": " + problem->message + "; drawn unskinned", problem->where, true);
        return;
    }
    skinnings_.emplace(prim.path, std::get<usda::Skinning>(std::move(*skinning)));
}

void UsdSceneHost::applySkinning(const usda::Prim& prim, const usda::Skinning& skinning, const usda::Attribute& attribute,
                         usda::Value& value, double time) {
    if (value.tupleSize != 3) return;
    std::string problem;
    std::vector<double> skinned;
    if (attribute.name == "points") {  // else normals or primvars:normals
        skinned = usda::skinPoints(stage_, skinning, value.numbers, time, &problem);
    } else {
        // Normals follow their points: one per point (vertex, varying: the schema's fallback), or one
        // per face-vertex of a mesh through its index, as UsdSkelImaging skins them.
        // XXX: constant and uniform normals are left unskinned.
        const usda::Attribute* points = prim.attribute("points");
        auto rest = points ? points->evaluate(time) : std::nullopt;
        const auto interpolation = attribute.metadata.find("interpolation");
        const std::string mode = interpolation != attribute.metadata.end() && !interpolation->second.strings.empty()
                                     ? interpolation->second.strings.front()
                                     : "vertex";
        const bool faceVarying = mode == "faceVarying" && prim.typeName == "Mesh";
        if (mode != "vertex" && mode != "varying" && !faceVarying) return;
        const usda::Attribute* indices = faceVarying ? prim.attribute("faceVertexIndices") : nullptr;
        auto indexValues = indices ? indices->evaluate(time) : std::nullopt;
        if (!rest || (faceVarying && !indexValues)) return;
        skinned = usda::skinNormals(stage_, skinning, value.numbers, indexValues ? &indexValues->numbers.vector() : nullptr,
                                    rest->size(), time, &problem);
    }
    if (!problem.empty())
        warnOnce("skinning:" + prim.path, prim.path + ": " + problem + (skinned.empty() ? "; drawn unskinned" : ""),
                 attribute.where, true);
    if (!skinned.empty()) value.numbers = std::move(skinned);
}

ObscuraStatus UsdSceneHost::computedPurpose(const usda::Prim& prim, ObscuraValue* out) {
    const usda::Attribute* opinion = stage_.purposeOpinion(prim);
    if (!opinion) return OBSCURA_ERROR_NOT_FOUND;  // the schema's fallback, default
    const usda::Value& value = *opinion->defaultValue;
    if (value.typeName != "token" || value.isArray || value.strings.size() != 1) {
        warnOnce("purpose:" + opinion->where.file + std::to_string(opinion->where.line),
                 prim.path + ": purpose is authored as " + opinion->typeName + ", not a token; default is used",
                 opinion->where);
        return OBSCURA_ERROR_NOT_FOUND;
    }
    return fill(value, out);
}

std::optional<PrimvarRead> UsdSceneHost::boundPrimvarRead(const usda::Prim& prim, const std::string& input) const {
    if (prim.typeName == "PointInstancer") return prototypesPrimvarRead(prim, input);
    auto material = boundMaterial(prim);
    if (!material) return std::nullopt;
    if (auto mapped = mappedSurfaces_.find(*material); mapped != mappedSurfaces_.end()) {
        const auto& reads = mapped->second.mapping.primvarReads;
        auto read = reads.find(input);
        return read == reads.end() ? std::nullopt : std::optional<PrimvarRead>(read->second);
    }
    auto surface = surfaces_.find(*material);
    if (surface == surfaces_.end()) return std::nullopt;
    return primvarRead(stage_, *surface->second, input);
}

// Hydra's instance primvars: an instancer's primvar reaches its prototypes' materials by name, so
// the read of its first prototype prim whose material reads `input` is the instancer's too (a
// nested instancer's prototypes are its own).
std::optional<PrimvarRead> UsdSceneHost::prototypesPrimvarRead(const usda::Prim& instancer, const std::string& input) const {
    const usda::Relationship* prototypes = instancer.relationship("prototypes");
    if (!prototypes) return std::nullopt;
    std::vector<const usda::Prim*> pending;
    for (const std::string& target : prototypes->targets)
        if (const usda::Prim* p = stage_.find(target)) pending.push_back(p);
    while (!pending.empty()) {
        const usda::Prim* p = pending.back();
        pending.pop_back();
        if (p->typeName == "PointInstancer" || p->typeName == "Material") continue;
        if (auto read = boundPrimvarRead(*p, input)) return read;
        for (auto it = p->children.rbegin(); it != p->children.rend(); ++it) pending.push_back(it->get());
    }
    return std::nullopt;
}

std::optional<std::string> UsdSceneHost::boundMaterial(const usda::Prim& prim) const {
    return resolveBoundMaterial(stage_, prim, drawableMaterial());
}

MaterialBindSubsets UsdSceneHost::bindSubsets(const usda::Prim& mesh, double time) const {
    return materialBindSubsets(mesh, time, [this](const usda::Prim& subset) {
        return resolveBoundMaterial(stage_, subset, drawableMaterial(), false);
    });
}

DrawableMaterial UsdSceneHost::drawableMaterial() const {
    // A surface Obscura draws: UsdPreviewSurface, a MaterialX node definition or OmniPBR (scan()).
    return [this](const std::string& path) {
        const usda::Prim* material = stage_.find(path);
        std::string problem;
        const usda::Prim* shader = material ? surfaceShader(*material, problem) : nullptr;
        return shader && (shaderId(*shader) == "UsdPreviewSurface" || isMaterialXShader(shaderId(*shader)) ||
                          isOmniPbrShader(*shader));
    };
}

const usda::Prim* UsdSceneHost::pointInstancerSpace(const usda::Prim& prim) const {
    for (const usda::Prim* p = &prim; p; p = p->parent) {
        auto it = prototypeRoots_.find(p->path);
        if (it != prototypeRoots_.end()) return it->second;
    }
    return nullptr;
}

const usda::Prim* UsdSceneHost::prototypeSpace(const usda::Prim& prim) const {
    if (const usda::Prim* space = pointInstancerSpace(prim)) return space;
    // The instancer places each instance, its root's transform included.
    const NativeInstancer* instancer = isInstancedGeometry(prim) ? nativeInstancing_.prototypeHolding(prim) : nullptr;
    return instancer ? instancer->prototype : nullptr;
}

ObscuraStatus UsdSceneHost::getNativeInstancerValue(const NativeInstancer& instancer, const std::string& attribute,
                                                    double time, ObscuraValue* out) {
    ReturnedValues& storage = returned();
    if (attribute == "prototypes") {
        storage.strings = {instancer.prototype->path};
        storage.stringPointers = {storage.strings[0].c_str()};
        *out = {OBSCURA_VALUE_PATH, 1, 1, storage.stringPointers.data()};
        return OBSCURA_OK;
    }
    // Each instance's visibility is its own (invisibleIds); the instancer itself is visible.
    auto value = nativeInstancing_.value(instancer, stage_, attribute, time);
    return value ? fill(*value, out) : OBSCURA_ERROR_NOT_FOUND;
}

ObscuraStatus UsdSceneHost::getValueThunk(void* user, const char* path, const char* attribute, double time,
                                          ObscuraValue* out) {
    if (!user || !path || !attribute || !out) return OBSCURA_ERROR_INVALID_ARGUMENT;
    auto* self = static_cast<UsdSceneHost*>(user);
    std::lock_guard lock(self->callbacks_);
    return self->getValue(path, attribute, time, out);
}

ObscuraStatus UsdSceneHost::getInterpolationThunk(void* user, const char* path, const char* attribute,
                                                  ObscuraInterpolation* out) {
    auto* self = static_cast<UsdSceneHost*>(user);
    std::lock_guard lock(self->callbacks_);
    const usda::Attribute* a = self->resolveAttribute(path, attribute);
    if (!a) return OBSCURA_ERROR_NOT_FOUND;
    auto it = a->metadata.find("interpolation");
    if (it == a->metadata.end() || it->second.strings.empty()) return OBSCURA_ERROR_NOT_FOUND;
    const std::string& i = it->second.strings[0];
    *out = i == "constant"      ? OBSCURA_INTERPOLATION_CONSTANT
           : i == "uniform"     ? OBSCURA_INTERPOLATION_UNIFORM
           : i == "varying"     ? OBSCURA_INTERPOLATION_VARYING
           : i == "faceVarying" ? OBSCURA_INTERPOLATION_FACE_VARYING
                                : OBSCURA_INTERPOLATION_VERTEX;
    return OBSCURA_OK;
}

ObscuraStatus UsdSceneHost::sampleTransformThunk(void* user, const char* path, double t0, double t1,
                                                 uint32_t maxSamples, double* times, double* matrices,
                                                 uint32_t* count) {
    auto* self = static_cast<UsdSceneHost*>(user);
    std::lock_guard lock(self->callbacks_);
    if (self->framingCamera_ && path == self->framingCamera_->path && maxSamples > 0) {
        times[0] = t0;
        std::copy(self->framingCamera_->transform.begin(), self->framingCamera_->transform.end(), matrices);
        *count = 1;
        return OBSCURA_OK;
    }
    if (self->nativeInstancing_.instancer(path) && maxSamples > 0) {
        // Instances are placed in world space.
        times[0] = t0;
        const usda::Matrix4 identity = usda::matrix4::identity();
        std::copy(identity.begin(), identity.end(), matrices);
        *count = 1;
        return OBSCURA_OK;
    }
    const usda::Prim* prim = self->stage_.find(path);
    if (!prim || maxSamples == 0) return OBSCURA_ERROR_NOT_FOUND;
    // The interval's ends and every authored sample time strictly inside it.
    std::vector<double> sampleTimes = {t0};
    for (double t : self->stage_.transformSampleTimes(*prim, t0, t1))
        if (t > t0 && t < t1) sampleTimes.push_back(t);
    if (t1 > t0) sampleTimes.push_back(t1);
    if (sampleTimes.size() > maxSamples) {
        sampleTimes.erase(sampleTimes.begin() + (maxSamples - 1), sampleTimes.end() - 1);
    }
    // Prototype meshes are placed relative to their prototype's space; instances do the rest.
    const usda::Prim* space = self->prototypeSpace(*prim);
    const usda::Matrix4 poleTurn = domePoleTurn(self->stage_, *prim, [&](const usda::Attribute& a, const std::string& token) {
        self->warnOnce("poleAxis:" + prim->path,
                       prim->path + ": poleAxis '" + token + "' is not scene, Y or Z; the stage's up axis is taken", a.where);
    });
    for (size_t i = 0; i < sampleTimes.size(); ++i) {
        times[i] = sampleTimes[i];
        auto m = usda::matrix4::multiply(poleTurn, self->stage_.worldTransform(*prim, sampleTimes[i]));
        if (space) m = usda::matrix4::multiply(m, usda::matrix4::inverse(self->stage_.worldTransform(*space, sampleTimes[i])));
        std::copy(m.begin(), m.end(), matrices + 16 * i);
    }
    *count = static_cast<uint32_t>(sampleTimes.size());
    return OBSCURA_OK;
}

}  // namespace obscura::harness
