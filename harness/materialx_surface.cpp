#include "harness/materialx_surface.h"

#include "harness/shading_network.h"

#include <algorithm>
#include <array>
#include <optional>
#include <set>

namespace obscura::harness {
namespace {

using Numbers = std::vector<double>;

// Connections through node graphs are followed this far (a cycle is an authoring error).
constexpr int kMaxFoldDepth = 32;

using Texture = MappedTexture;  // ND_tiledimage's placement in its transform

// A folded input: a constant (`offset`), or a texture's texel or the prim's primvar (an
// ND_geompropvalue: a PrimvarRead, its fallback the node's inputs:default) times `scale` plus
// `offset`, per component.
struct Signal {
    Numbers offset;
    Numbers scale;
    std::optional<Texture> texture;
    std::optional<PrimvarRead> primvar;
    bool varies() const { return texture || primvar; }
};

Signal constant(Numbers value) { return Signal{std::move(value), {}, std::nullopt, std::nullopt}; }

Numbers broadcast(const Numbers& v, size_t width) {
    if (v.size() == width || v.empty()) return v.empty() ? Numbers(width, 0.0) : v;
    if (v.size() == 1) return Numbers(width, v[0]);
    Numbers out(v.begin(), v.begin() + long(std::min(v.size(), width)));
    out.resize(width, out.empty() ? 0.0 : out.back());
    return out;
}

// Component-wise `a * b` (broadcast to the wider of the two).
Numbers times(const Numbers& a, const Numbers& b) {
    const size_t width = std::max(a.size(), b.size());
    Numbers x = broadcast(a, width), y = broadcast(b, width);
    for (size_t i = 0; i < width; ++i) x[i] *= y[i];
    return x;
}

Numbers plus(const Numbers& a, const Numbers& b) {
    const size_t width = std::max(a.size(), b.size());
    Numbers x = broadcast(a, width), y = broadcast(b, width);
    for (size_t i = 0; i < width; ++i) x[i] += y[i];
    return x;
}

// a * k for a constant k: a texture's (primvar's) scale and offset both scale.
Signal scaled(Signal a, const Numbers& k) {
    if (a.varies()) a.scale = times(a.scale, k);
    a.offset = times(a.offset, k);
    return a;
}

std::optional<Signal> multiply(const Signal& a, const Signal& b) {
    if (a.varies() && b.varies()) return std::nullopt;  // a product of two textures (primvars) is neither
    if (b.varies()) return scaled(b, a.offset);
    return scaled(a, b.offset);
}

std::optional<Signal> add(const Signal& a, const Signal& b) {
    if (a.varies() && b.varies()) return std::nullopt;
    Signal out = a.varies() ? a : b;
    out.offset = plus(a.offset, b.offset);
    return out;
}

usda::Value numbers(const char* type, Numbers n) { return numbersValue(type, std::move(n)); }

usda::Value token(std::string text) {
    usda::Value v;
    v.typeName = "token";
    v.strings = {std::move(text)};
    return v;
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Reads networks into signals, recording what cannot map.
class Folder {
public:
    Folder(const usda::Stage& stage, double time, std::vector<MaterialProblem>& problems)
        : stage_(stage), time_(time), problems_(problems) {}

    // The input `name` of `node`: its value, what its connection folds to, or `fallback`.
    std::optional<Signal> input(const usda::Prim& node, const std::string& name, const Numbers& fallback, int depth = 0) {
        const usda::Attribute* attribute = node.attribute("inputs:" + name);
        if (!attribute) return constant(fallback);
        if (!attribute->connection) return valueOf(*attribute, fallback);
        auto source = connectionSource(stage_, *attribute);
        if (auto* reason = std::get_if<std::string>(&source)) {
            problem(attribute->where, node.path + ".inputs:" + name + ": " + *reason);
            return std::nullopt;
        }
        const ConnectionSource& found = std::get<ConnectionSource>(source);
        if (found.attribute) return valueOf(*found.attribute, fallback);
        return fold(*found.prim, depth + 1);
    }

    void problem(const usda::SourceLocation& where, std::string message) {
        if (reported_.insert(message).second) problems_.push_back({std::move(message), where});
    }

private:
    std::optional<Signal> valueOf(const usda::Attribute& attribute, const Numbers& fallback) const {
        auto value = attribute.evaluate(time_);
        return constant(value && !value->numbers.empty() ? value->numbers.vector() : fallback);
    }

    std::optional<Signal> unmappable(const usda::Prim& node, const std::string& id) {
        problem(node.where, node.path + " (" + id + ") cannot be folded into a constant or a texture");
        return std::nullopt;
    }

    std::optional<Signal> fold(const usda::Prim& node, int depth) {
        const std::string id = shaderId(node);
        if (depth > kMaxFoldDepth) {
            problem(node.where, node.path + ": its network is deeper than " + std::to_string(kMaxFoldDepth) + " nodes");
            return std::nullopt;
        }
        auto in = [&](const char* name, const Numbers& fallback) { return input(node, name, fallback, depth); };
        if (startsWith(id, "ND_image_") || startsWith(id, "ND_tiledimage_")) return image(node, id, depth);
        if (startsWith(id, "ND_geompropvalue_")) return geomprop(node, id);
        if (startsWith(id, "ND_constant_")) return in("value", {0.0});
        if (startsWith(id, "ND_dot_") || startsWith(id, "ND_convert_")) return in("in", {0.0});
        if (startsWith(id, "ND_multiply_") || startsWith(id, "ND_add_") || startsWith(id, "ND_subtract_")) {
            const bool product = startsWith(id, "ND_multiply_");
            auto a = in("in1", {0.0});
            auto b = in("in2", {product ? 1.0 : 0.0});
            if (!a || !b) return std::nullopt;
            if (startsWith(id, "ND_subtract_")) b = scaled(*b, {-1.0});
            auto out = product ? multiply(*a, *b) : add(*a, *b);
            return out ? out : unmappable(node, id);
        }
        if (startsWith(id, "ND_mix_")) {
            auto fg = in("fg", {0.0}), bg = in("bg", {0.0}), weight = in("mix", {0.0});
            if (!fg || !bg || !weight) return std::nullopt;
            if (weight->varies()) return unmappable(node, id);
            auto out = add(scaled(*fg, weight->offset), scaled(*bg, plus(scaled(*weight, {-1.0}).offset, {1.0})));
            return out ? out : unmappable(node, id);
        }
        if (startsWith(id, "ND_normalmap")) {
            // Tangent-space normals are stored as n * 0.5 + 0.5.
            auto encoded = in("in", {0.5, 0.5, 1.0});
            auto strength = in("scale", {1.0});
            if (strength && (strength->varies() || broadcast(strength->offset, 1)[0] != 1.0))
                problem(node.where, node.path + " (" + id + "): inputs:scale other than 1 is not applied");
            if (!encoded) return std::nullopt;
            Signal out = scaled(*encoded, {2.0});
            out.offset = plus(out.offset, {-1.0});
            return out;
        }
        if (startsWith(id, "ND_extract_")) {
            auto from = in("in", {0.0});
            auto index = in("index", {0.0});
            if (!from || !index || index->varies() || from->primvar) return from ? unmappable(node, id) : std::nullopt;
            const size_t i = size_t(std::clamp(broadcast(index->offset, 1)[0], 0.0, 3.0));
            Signal out = *from;
            out.offset = {broadcast(from->offset, 4)[i]};
            if (out.texture) {
                if (out.texture->channel != "rgb") return unmappable(node, id);
                out.scale = {broadcast(from->scale, 4)[i]};
                out.texture->channel = std::string(1, "rgba"[i]);
            }
            return out;
        }
        return unmappable(node, id);
    }

    // The primvar an image reads: ND_texcoord_vector2's set (index 0 is "st") or
    // ND_geompropvalue_vector2's geomprop.
    std::string texcoordPrimvar(const usda::Prim& image) {
        const usda::Attribute* texcoord = image.attribute("inputs:texcoord");
        const usda::Prim* reader = texcoord ? connectedShader(stage_, *texcoord) : nullptr;
        if (!reader) return "st";
        const std::string id = shaderId(*reader);
        if (startsWith(id, "ND_geompropvalue_")) {
            const usda::Attribute* property = reader->attribute("inputs:geomprop");
            auto name = property ? property->evaluate(time_) : std::nullopt;
            if (name && !name->strings.empty() && !name->strings[0].empty()) return name->strings[0];
        } else if (startsWith(id, "ND_texcoord_")) {
            const usda::Attribute* index = reader->attribute("inputs:index");
            auto set = index ? index->evaluate(time_) : std::nullopt;
            if (set && !set->numbers.empty() && set->numbers[0] != 0) return "st" + std::to_string(int(set->numbers[0]));
            return "st";
        }
        problem(reader->where, image.path + ".inputs:texcoord: " + reader->path + " (" + id +
                                   ") is neither ND_texcoord nor ND_geompropvalue; primvars:st is read");
        return "st";
    }

    std::optional<Signal> image(const usda::Prim& node, const std::string& id, int depth) {
        Texture texture;
        const usda::Attribute* input = node.attribute("inputs:file");
        const usda::Attribute* file = input ? valueProducingAttribute(stage_, *input) : nullptr;
        auto asset = file ? file->evaluate(time_) : std::nullopt;
        if (!asset || asset->strings.empty() || asset->strings[0].empty()) {
            problem(node.where, node.path + " (" + id + ") has no inputs:file");
            return std::nullopt;
        }
        texture.file = resolveAssetPath(asset->strings[0], *file);
        const bool color = id.find("color") != std::string::npos;
        // MaterialX transforms colour images from their colorspace; other data is read as it is.
        if (const auto space = file->metadata.find("colorSpace"); color && space != file->metadata.end() &&
                                                                   !space->second.strings.empty()) {
            const std::string& name = space->second.strings[0];
            if (name == "srgb_texture" || name == "sRGB" || name == "srgb") texture.colorSpace = "sRGB";
        }
        auto address = [&](const char* name) {
            const usda::Attribute* a = node.attribute(std::string("inputs:") + name);
            const usda::Attribute* holder = a ? valueProducingAttribute(stage_, *a) : nullptr;
            auto v = holder ? holder->evaluate(time_) : std::nullopt;
            const std::string m = v && !v->strings.empty() ? v->strings[0] : "periodic";
            return m == "clamp" ? "clamp" : m == "mirror" ? "mirror" : m == "constant" ? "black" : "repeat";
        };
        texture.wrapS = address("uaddressmode");
        texture.wrapT = address("vaddressmode");
        if (startsWith(id, "ND_tiledimage_")) texture.transform = tiling(node, id, depth);
        texture.st = texcoordPrimvar(node);
        const size_t width = id.ends_with("_float") ? 1 : 3;
        texture.channel = width == 1 ? "r" : "rgb";
        return Signal{Numbers(width, 0.0), Numbers(width, 1.0), texture, std::nullopt};
    }

    // The prim's primvar `inputs:geomprop` names, as a vertex colour (float: its first component),
    // or the node's inputs:default where the prim has none.
    std::optional<Signal> geomprop(const usda::Prim& node, const std::string& id) {
        const size_t width = id == "ND_geompropvalue_float" ? 1
                           : id == "ND_geompropvalue_color3" || id == "ND_geompropvalue_vector3" ? 3 : 0;
        if (width == 0) return unmappable(node, id);
        const usda::Attribute* property = node.attribute("inputs:geomprop");
        const usda::Attribute* holder = property ? valueProducingAttribute(stage_, *property) : nullptr;
        auto name = holder ? holder->evaluate(time_) : std::nullopt;
        if (!name || name->strings.empty() || name->strings[0].empty()) {
            problem(node.where, node.path + " (" + id + ") names no inputs:geomprop");
            return std::nullopt;
        }
        const usda::Attribute* fallback = node.attribute("inputs:default");
        if (fallback) fallback = valueProducingAttribute(stage_, *fallback);
        return Signal{Numbers(width, 0.0), Numbers(width, 1.0), std::nullopt, PrimvarRead{name->strings[0], fallback}};
    }

    // ND_tiledimage's placement of the image; the identity, reported, where an input is textured
    // or the result is not finite.
    StTransform tiling(const usda::Prim& node, const std::string& id, int depth) {
        std::array<std::array<double, 2>, 4> values{};
        const std::array<std::pair<const char*, double>, 4> inputs = {
            {{"uvtiling", 1.0}, {"uvoffset", 0.0}, {"realworldimagesize", 1.0}, {"realworldtilesize", 1.0}}};
        for (size_t i = 0; i < inputs.size(); ++i) {
            auto signal = input(node, inputs[i].first, {inputs[i].second, inputs[i].second}, depth);
            if (!signal) return {};
            if (signal->varies()) {
                problem(node.where, node.path + " (" + id + "): a textured inputs:" + inputs[i].first + " is not applied");
                return {};
            }
            const Numbers v = broadcast(signal->offset, 2);
            values[i] = {v[0], v[1]};
        }
        auto placed = tiledImage(values[0], values[1], values[2], values[3]);
        if (!placed) {
            problem(node.where, node.path + " (" + id + "): uvtiling, uvoffset and the real-world sizes must give " +
                                    "finite coordinates; the image is not tiled");
            return {};
        }
        return *placed;
    }

    const usda::Stage& stage_;
    double time_;
    std::vector<MaterialProblem>& problems_;
    std::set<std::string> reported_;
};

// One UsdPreviewSurface input and where a surface model keeps it.
struct Entry {
    const char* usdInput;                // "diffuseColor"
    const char* input;                   // "base_color"
    Numbers fallback;                    // the model's default
    const char* weight = nullptr;        // an input it is multiplied by ("base"), or none
    double weightFallback = 1.0;
    double unit = 1.0;                   // the model's unit in UsdPreviewSurface's (turns to degrees: 360)
};

struct SurfaceModel {
    const char* idPrefix;
    std::vector<Entry> entries;
    std::vector<const char*> leftOut;  // lobes Obscura's model has no place for
};

// Defaults from each node definition (MaterialX standard library, glTF and OpenPBR specs).
const std::vector<SurfaceModel>& surfaceModels() {
    static const std::vector<SurfaceModel> kModels = {
        {"ND_standard_surface_",
         {{"diffuseColor", "base_color", {1, 1, 1}, "base", 0.8},
          {"metallic", "metalness", {0}},
          {"roughness", "specular_roughness", {0.2}},
          {"emissiveColor", "emission_color", {1, 1, 1}, "emission", 0.0},
          {"opacity", "opacity", {1, 1, 1}},
          {"normal", "normal", {}},
          {"clearcoat", "coat", {0}},
          {"clearcoatRoughness", "coat_roughness", {0.1}},
          {"ior", "specular_IOR", {1.5}},
          {"obscura:anisotropy", "specular_anisotropy", {0}},
          // Standard Surface turns the anisotropy's direction by a fraction of a full turn.
          {"obscura:anisotropyRotation", "specular_rotation", {0}, nullptr, 1.0, 360.0}},
         {"transmission", "subsurface", "sheen", "thin_film_thickness"}},
        {"ND_UsdPreviewSurface_",
         {{"diffuseColor", "diffuseColor", {0.18, 0.18, 0.18}},
          {"metallic", "metallic", {0}},
          {"roughness", "roughness", {0.5}},
          {"emissiveColor", "emissiveColor", {0, 0, 0}},
          {"opacity", "opacity", {1}},
          {"opacityThreshold", "opacityThreshold", {0}},
          {"normal", "normal", {}},
          {"occlusion", "occlusion", {1}},
          {"clearcoat", "clearcoat", {0}},
          {"clearcoatRoughness", "clearcoatRoughness", {0.01}},
          {"ior", "ior", {1.5}},
          {"specularColor", "specularColor", {0, 0, 0}},
          {"useSpecularWorkflow", "useSpecularWorkflow", {0}}},
         {"displacement"}},
        {"ND_gltf_pbr_",
         {{"diffuseColor", "base_color", {1, 1, 1}},
          {"metallic", "metallic", {1}},
          {"roughness", "roughness", {1}},
          {"emissiveColor", "emissive", {0, 0, 0}, "emissive_strength", 1.0},
          {"normal", "normal", {}},
          {"occlusion", "occlusion", {1}},
          {"clearcoat", "clearcoat", {0}},
          {"clearcoatRoughness", "clearcoat_roughness", {0}},
          {"ior", "ior", {1.5}}},
         {"transmission", "sheen_color", "iridescence", "thickness"}},
        {"ND_open_pbr_surface_",
         {{"diffuseColor", "base_color", {0.8, 0.8, 0.8}, "base_weight", 1.0},
          {"metallic", "base_metalness", {0}},
          {"roughness", "specular_roughness", {0.3}},
          // XXX: OpenPBR's emission is in nits; it is taken as UsdPreviewSurface's emissiveColor.
          {"emissiveColor", "emission_color", {1, 1, 1}, "emission_luminance", 0.0},
          {"opacity", "geometry_opacity", {1}},
          {"normal", "geometry_normal", {}},
          {"clearcoat", "coat_weight", {0}},
          {"clearcoatRoughness", "coat_roughness", {0}},
          {"ior", "specular_ior", {1.5}}},
         {"transmission_weight", "subsurface_weight", "fuzz_weight", "thin_film_weight"}},
    };
    return kModels;
}

bool isColorInput(const std::string& usdInput) {
    return usdInput == "diffuseColor" || usdInput == "emissiveColor" || usdInput == "specularColor" || usdInput == "normal";
}

// A primvar read as diffuseColor (times a constant: the vertex colour's scale, Standard Surface's
// base) or as opacity; anything else is reported and left at its default.
void storePrimvarRead(MaterialXMapping& out, Folder& folder, const usda::Prim& surface, const std::string& usdInput,
                      const std::string& from, const Signal& signal) {
    const size_t width = isColorInput(usdInput) ? 3 : 1;
    const Numbers scale = broadcast(signal.scale, width), offset = broadcast(signal.offset, width);
    const bool unscaled = std::all_of(scale.begin(), scale.end(), [](double s) { return s == 1.0; });
    const bool noOffset = std::all_of(offset.begin(), offset.end(), [](double o) { return o == 0.0; });
    const std::string what = surface.path + ".inputs:" + from + " reads primvar " + signal.primvar->primvar;
    if (usdInput != "diffuseColor" && usdInput != "opacity") {
        folder.problem(surface.where, what + ", and Obscura's material model reads primvars on diffuseColor and opacity " +
                                          "only; its default is used");
        return;
    }
    if (!noOffset || (usdInput == "opacity" && !unscaled)) {
        folder.problem(surface.where, what + (usdInput == "opacity" ? " scaled or offset" : " offset") +
                                          ", which Obscura's material model does not apply; its default is used");
        return;
    }
    out.values["obscura:" + usdInput + ":primvar"] = token(signal.primvar->primvar);
    if (usdInput == "diffuseColor") out.values["inputs:diffuseColor"] = numbers("float3", scale);
    out.primvarReads["inputs:" + usdInput] = *signal.primvar;
}

void store(MaterialXMapping& out, Folder& folder, const usda::Prim& surface, const std::string& usdInput,
           const std::string& from, Signal signal) {
    if (signal.primvar) return storePrimvarRead(out, folder, surface, usdInput, from, signal);
    const size_t width = isColorInput(usdInput) ? 3 : 1;
    if (signal.texture && !isTexturableInput("inputs:" + usdInput)) {
        folder.problem(surface.where, surface.path + ".inputs:" + from + " is textured, and Obscura's material model " +
                                          "takes no texture on " + usdInput + "; its default is used");
        return;
    }
    if (!signal.texture) {
        if (signal.offset.empty()) return;
        out.values["inputs:" + usdInput] =
            numbers(width == 3 ? "float3" : usdInput == "useSpecularWorkflow" ? "int" : "float",
                    broadcast(signal.offset, width));
        return;
    }
    Texture t = *signal.texture;
    if (width == 1 && t.channel == "rgb") t.channel = "r";
    storeTexture(out, usdInput, t, signal.scale, signal.offset);
}

// A surface of a kind this mapping does not know: its base colour, under the names surfaces use.
void mapFallback(MaterialXMapping& out, Folder& folder, const usda::Prim& surface, const std::string& id) {
    folder.problem(surface.where, surface.path + " (" + id +
                                      ") is not a surface Obscura's material model maps; drawn with its base colour");
    // MDL's OmniPBR-like and OmniSurface names last.
    for (const char* name : {"base_color", "diffuseColor", "diffuse_color", "color", "albedo", "base_colour",
                             "diffuse_color_constant", "diffuse_reflection_color"}) {
        if (!surface.attribute(std::string("inputs:") + name)) continue;
        if (auto signal = folder.input(surface, name, {0.18, 0.18, 0.18}))
            store(out, folder, surface, "diffuseColor", name, *signal);
        return;
    }
}

}  // namespace

usda::Value numbersValue(const char* type, std::vector<double> n) {
    usda::Value v;
    v.typeName = type;
    v.tupleSize = int(n.size());
    v.numbers = std::move(n);
    return v;
}

void storeTexture(MaterialXMapping& out, const std::string& usdInput, const MappedTexture& t, std::vector<double> scale,
                  std::vector<double> bias) {
    const std::string prefix = "obscura:" + usdInput + ":";
    out.values[prefix + "file"] = token(t.file);
    out.values[prefix + "channel"] = token(t.channel);
    out.values[prefix + "st"] = token(t.st);
    out.values[prefix + "transformS"] = numbers("float3", Numbers(t.transform.s.begin(), t.transform.s.end()));
    out.values[prefix + "transformT"] = numbers("float3", Numbers(t.transform.t.begin(), t.transform.t.end()));
    out.values[prefix + "wrapS"] = token(t.wrapS);
    out.values[prefix + "wrapT"] = token(t.wrapT);
    out.values[prefix + "sourceColorSpace"] = token(t.colorSpace);
    scale = broadcast(scale, 3);
    bias = broadcast(bias, 3);
    scale.push_back(1.0);
    bias.push_back(0.0);
    out.values[prefix + "scale"] = numbers("float4", std::move(scale));
    out.values[prefix + "bias"] = numbers("float4", std::move(bias));
    if (out.stPrimvar == "st") out.stPrimvar = t.st;
}

bool isMaterialXShader(const std::string& shaderId) { return startsWith(shaderId, "ND_"); }

MaterialXMapping mapMaterialXSurface(const usda::Stage& stage, const usda::Prim& surface, double time) {
    MaterialXMapping out;
    Folder folder(stage, time, out.problems);
    // An MDL shader has no info:id: its module's material names it.
    std::string id = shaderId(surface);
    if (const usda::Attribute* mdl = id.empty() ? surface.attribute("info:mdl:sourceAsset:subIdentifier") : nullptr)
        if (auto name = mdl->evaluate(time); name && !name->strings.empty()) id = "MDL " + name->strings[0];
    const auto model = std::find_if(surfaceModels().begin(), surfaceModels().end(),
                                    [&](const SurfaceModel& m) { return startsWith(id, m.idPrefix); });
    if (model == surfaceModels().end()) {
        mapFallback(out, folder, surface, id);
        return out;
    }
    for (const Entry& entry : model->entries) {
        const usda::Attribute* authored = surface.attribute(std::string("inputs:") + entry.input);
        const usda::Attribute* weightAuthored =
            entry.weight ? surface.attribute(std::string("inputs:") + entry.weight) : nullptr;
        if (entry.fallback.empty() && !authored) continue;  // a normal is only ever connected
        auto signal = folder.input(surface, entry.input, entry.fallback);
        if (!signal) signal = constant(entry.fallback);  // reported; the model's default
        if (entry.weight) {
            auto weight = folder.input(surface, entry.weight, {entry.weightFallback});
            if (!weight || weight->varies()) {
                if (weight) folder.problem(weightAuthored->where, surface.path + ".inputs:" + entry.weight +
                                                                      " is textured; its constant default is used");
                weight = constant({entry.weightFallback});
            }
            signal = multiply(*signal, *weight);
        }
        if (entry.unit != 1.0) signal = scaled(*signal, {entry.unit});
        store(out, folder, surface, entry.usdInput, entry.input, *signal);
    }
    // glTF's alpha mode: opaque ignores alpha, mask cuts out at alphaCutoff, blend is transparent.
    if (startsWith(id, "ND_gltf_pbr_")) {
        auto mode = folder.input(surface, "alpha_mode", {0});
        const double alphaMode = mode && !mode->varies() ? broadcast(mode->offset, 1)[0] : 0.0;
        if (alphaMode != 0) {
            if (auto alpha = folder.input(surface, "alpha", {1})) store(out, folder, surface, "opacity", "alpha", *alpha);
            if (alphaMode == 1)
                if (auto cutoff = folder.input(surface, "alpha_cutoff", {0.5}))
                    store(out, folder, surface, "opacityThreshold", "alpha_cutoff", *cutoff);
        }
    }
    std::vector<std::string> leftOut;
    for (const char* lobe : model->leftOut) {
        const usda::Attribute* a = surface.attribute(std::string("inputs:") + lobe);
        auto v = a && !a->connection ? a->evaluate(time) : std::nullopt;
        if (a && (a->connection || (v && std::any_of(v->numbers.begin(), v->numbers.end(), [](double x) { return x != 0; }))))
            leftOut.push_back(lobe);
    }
    if (!leftOut.empty()) {
        std::string names;
        for (const std::string& name : leftOut) names += (names.empty() ? "" : ", ") + name;
        folder.problem(surface.where, surface.path + " (" + id + "): " + names + " not in Obscura's material model; left out");
    }
    return out;
}

}  // namespace obscura::harness
