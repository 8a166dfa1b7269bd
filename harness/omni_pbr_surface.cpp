#include "harness/omni_pbr_surface.h"

#include <algorithm>
#include <cmath>

namespace obscura::harness {
namespace {

using Numbers = std::vector<double>;

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

usda::Value numbers(const char* type, Numbers n) { return numbersValue(type, std::move(n)); }

// Reads one shader's inputs, recording what cannot map.
class Inputs {
public:
    Inputs(const usda::Stage& stage, const usda::Prim& shader, double time, MaterialXMapping& out)
        : stage_(stage), shader_(shader), time_(time), out_(out) {}

    Numbers number(const std::string& name, Numbers fallback) const {
        auto value = evaluated(name);
        if (!value || value->numbers.size() != fallback.size()) return fallback;
        Numbers n = value->numbers.vector();
        return std::all_of(n.begin(), n.end(), [](double x) { return std::isfinite(x); }) ? n : fallback;
    }
    double scalar(const std::string& name, double fallback) const { return number(name, {fallback})[0]; }
    bool flag(const std::string& name) const { return scalar(name, 0.0) != 0.0; }

    // An asset input: the texture it names, nullopt when it names none.
    std::optional<MappedTexture> texture(const std::string& name, bool color) const {
        const usda::Attribute* input = shader_.attribute("inputs:" + name);
        const usda::Attribute* holder = input ? valueProducingAttribute(stage_, *input) : nullptr;
        auto asset = holder ? holder->evaluate(time_) : std::nullopt;
        if (!asset || asset->strings.empty() || asset->strings[0].empty()) return std::nullopt;
        MappedTexture t;
        t.file = resolveAssetPath(asset->strings[0], *holder);
        // MDL's "auto" gamma reads colours as sRGB; colorSpace metadata says so explicitly.
        const auto space = holder->metadata.find("colorSpace");
        const std::string declared = space != holder->metadata.end() && !space->second.strings.empty()
                                         ? space->second.strings[0]
                                         : "auto";
        t.colorSpace = declared == "raw" ? "raw" : declared == "sRGB" || color ? "sRGB" : "raw";
        // OmniPBR's placement of every texture: scaled, rotated (degrees), then translated.
        const Numbers scale = number("texture_scale", {1.0, 1.0}), translate = number("texture_translate", {0.0, 0.0});
        t.transform = transform2d({scale[0], scale[1]}, scalar("texture_rotate", 0.0), {translate[0], translate[1]});
        return t;
    }

    void problem(const std::string& message) {
        out_.problems.push_back({shader_.path + " (OmniPBR): " + message, shader_.where});
    }
    bool authored(const std::string& name) const { return evaluated(name).has_value(); }

private:
    std::optional<usda::Value> evaluated(const std::string& name) const {
        const usda::Attribute* input = shader_.attribute("inputs:" + name);
        const usda::Attribute* holder = input ? valueProducingAttribute(stage_, *input) : nullptr;
        auto value = holder ? holder->evaluate(time_) : std::nullopt;
        return value && !value->empty() ? value : std::nullopt;
    }

    const usda::Stage& stage_;
    const usda::Prim& shader_;
    double time_;
    MaterialXMapping& out_;
};

// A scalar input with an optional texture blended in by `influence`: lerp(constant, texel, influence).
void storeBlended(MaterialXMapping& out, const std::string& usdInput, double constant,
                  const std::optional<MappedTexture>& texture, double influence, const std::string& channel) {
    if (!texture || influence == 0.0) {
        out.values["inputs:" + usdInput] = numbers("float", {constant});
        return;
    }
    MappedTexture t = *texture;
    t.channel = channel;
    storeTexture(out, usdInput, t, {influence}, {constant * (1.0 - influence)});
}

}  // namespace

bool isOmniPbrShader(const usda::Prim& shader) {
    const usda::Attribute* source = shader.attribute("info:mdl:sourceAsset");
    auto asset = source ? source->evaluate(0.0) : std::nullopt;
    if (!asset || asset->strings.empty()) return false;
    const std::string& file = asset->strings[0];
    return endsWith(file, "OmniPBR.mdl") || endsWith(file, "OmniPBR_ClearCoat.mdl") || endsWith(file, "OmniPBR_Opacity.mdl") ||
           endsWith(file, "OmniPBR_ClearCoat_Opacity.mdl");
}

MaterialXMapping mapOmniPbrSurface(const usda::Stage& stage, const usda::Prim& shader, double time) {
    MaterialXMapping out;
    Inputs in(stage, shader, time, out);
    // Base colour (OmniPBR.mdl): the diffuse texture, adjusted by albedo_brightness and albedo_add,
    // or the constant colour; either times diffuse_tint.
    const Numbers tint = in.number("diffuse_tint", {1, 1, 1});
    if (auto diffuse = in.texture("diffuse_texture", true)) {
        const double brightness = in.scalar("albedo_brightness", 1.0), add = in.scalar("albedo_add", 0.0);
        Numbers scale(3), bias(3);
        for (size_t i = 0; i < 3; ++i) scale[i] = brightness * tint[i], bias[i] = add * tint[i];
        storeTexture(out, "diffuseColor", *diffuse, scale, bias);
        if (in.scalar("albedo_desaturation", 0.0) != 0.0) in.problem("albedo_desaturation is not applied");
    } else {
        Numbers color = in.number("diffuse_color_constant", {0.2, 0.2, 0.2});
        for (size_t i = 0; i < 3; ++i) color[i] *= tint[i];
        out.values["inputs:diffuseColor"] = numbers("float3", color);
    }
    // Roughness and metallic: constants, or textures blended in by their influence; an ORM texture
    // carries occlusion, roughness and metallic in r, g and b.
    const bool orm = in.flag("enable_ORM_texture");
    const auto ormTexture = orm ? in.texture("ORM_texture", false) : std::nullopt;
    storeBlended(out, "roughness", in.scalar("reflection_roughness_constant", 0.5),
                 ormTexture ? ormTexture : in.texture("reflectionroughness_texture", false),
                 ormTexture ? 1.0 : in.scalar("reflection_roughness_texture_influence", 0.0), ormTexture ? "g" : "r");
    storeBlended(out, "metallic", in.scalar("metallic_constant", 0.0),
                 ormTexture ? ormTexture : in.texture("metallic_texture", false),
                 ormTexture ? 1.0 : in.scalar("metallic_texture_influence", 0.0), ormTexture ? "b" : "r");
    if (ormTexture) {
        MappedTexture occlusion = *ormTexture;
        occlusion.channel = "r";
        storeTexture(out, "occlusion", occlusion, {1.0}, {0.0});
    }
    // specular_level scales the dielectric's reflectance at normal incidence, 0.08 x level (0.04
    // at its default 0.5): the ior that reflects as much.
    const double f0 = std::clamp(0.08 * in.scalar("specular_level", 0.5), 0.0, 0.99);
    out.values["inputs:ior"] = numbers("float", {(1.0 + std::sqrt(f0)) / (1.0 - std::sqrt(f0))});
    // Emission: emissive_color (or its texture) times emissive_intensity, when enabled.
    if (in.flag("enable_emission")) {
        const double intensity = in.scalar("emissive_intensity", 40.0);
        Numbers color = in.number("emissive_color", {1.0, 0.1, 0.1});
        if (auto emissive = in.texture("emissive_color_texture", true)) {
            storeTexture(out, "emissiveColor", *emissive, {intensity, intensity, intensity}, {0.0});
        } else {
            for (double& c : color) c *= intensity;
            out.values["inputs:emissiveColor"] = numbers("float3", color);
        }
    }
    // Tangent-space normal map, stored as n * 0.5 + 0.5.
    if (auto normal = in.texture("normalmap_texture", false)) {
        normal->colorSpace = "raw";
        storeTexture(out, "normal", *normal, {2.0, 2.0, 2.0}, {-1.0, -1.0, -1.0});
        if (in.scalar("bump_factor", 1.0) != 1.0) in.problem("bump_factor other than 1 is not applied");
    }
    // Opacity, when enabled: the constant or the texture's channel; a threshold cuts out.
    if (in.flag("enable_opacity")) {
        if (auto opacity = in.texture("opacity_texture", false)) {
            opacity->channel = "r";
            storeTexture(out, "opacity", *opacity, {1.0}, {0.0});
        } else {
            out.values["inputs:opacity"] = numbers("float", {std::clamp(in.scalar("opacity_constant", 1.0), 0.0, 1.0)});
        }
        out.values["inputs:opacityThreshold"] = numbers("float", {std::clamp(in.scalar("opacity_threshold", 0.0), 0.0, 1.0)});
    }
    // The clear-coat variant's coat.
    if (in.flag("enable_clearcoat")) {
        out.values["inputs:clearcoat"] = numbers("float", {std::clamp(in.scalar("clearcoat_weight", 1.0), 0.0, 1.0)});
        out.values["inputs:clearcoatRoughness"] =
            numbers("float", {std::clamp(in.scalar("clearcoat_reflection_roughness", 0.0), 0.0, 1.0)});
    }
    if (in.flag("project_uvw")) in.problem("project_uvw (projected texture coordinates) is not applied; primvars:st is read");
    return out;
}

}  // namespace obscura::harness
