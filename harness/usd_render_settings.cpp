#include "harness/usd_render_settings.h"

#include <algorithm>
#include <map>

namespace obscura::harness {
namespace {

// A RenderVar's source as Hydra's AOV names (HdAovTokens) and the names Obscura writes: "raw" and
// "intrinsic" sources name an AOV; the one light path expression Obscura answers is the whole
// beauty ("C.*"), which is its colour.
std::optional<std::string> aovOfRenderVar(const std::string& sourceType, const std::string& sourceName) {
    static const std::map<std::string, std::string> kAovs = {
        {"color", "color"},   {"depth", "depth"},         {"normal", "normal"},   {"Neye", "normal"},
        {"albedo", "albedo"}, {"motion", "motion"},       {"primId", "primId"},   {"instanceId", "instanceId"},
    };
    if (sourceType == "lpe") return sourceName == "C.*" ? std::optional<std::string>("color") : std::nullopt;
    if (sourceType != "raw" && sourceType != "intrinsic") return std::nullopt;
    auto it = kAovs.find(sourceName);
    return it == kAovs.end() ? std::nullopt : std::optional(it->second);
}

class Reader {
public:
    Reader(const usda::Stage& stage, std::vector<HostMessage>& messages) : stage_(stage), messages_(messages) {}

    void warn(const usda::Prim& prim, const std::string& text, const usda::SourceLocation& where) {
        messages_.push_back({false, prim.path + ": " + text, where});
    }

    // An authored value of one of `types`, else a warning and nothing.
    std::optional<usda::Value> value(const usda::Prim& prim, const char* name, std::initializer_list<const char*> types) {
        const usda::Attribute* attribute = prim.attribute(name);
        auto value = attribute ? attribute->evaluate(0.0) : std::nullopt;
        if (!value || value->empty()) return std::nullopt;
        for (const char* type : types)
            if (value->typeName == type) return value;
        std::string expected;
        for (const char* type : types) expected += (expected.empty() ? "" : " or ") + std::string(type);
        warn(prim, std::string(name) + " is a " + attribute->typeName + ", not a " + expected + "; ignored",
             attribute->where);
        return std::nullopt;
    }

    // The targets of a relationship that name prims of `type`; others are reported.
    std::vector<const usda::Prim*> targets(const usda::Prim& prim, const char* name, const char* type) {
        std::vector<const usda::Prim*> out;
        const usda::Relationship* rel = prim.relationship(name);
        if (!rel) return out;
        for (const std::string& path : rel->targets) {
            const usda::Prim* target = stage_.find(path);
            if (!target) warn(prim, std::string(name) + " target <" + path + "> does not exist; ignored", prim.where);
            else if (target->typeName != type)
                warn(prim, std::string(name) + " target <" + path + "> is a " +
                               (target->typeName.empty() ? "typeless prim" : target->typeName) + ", not a " + type +
                               "; ignored",
                     prim.where);
            else out.push_back(target);
        }
        return out;
    }

    // UsdRenderSettingsBase: camera, resolution, pixelAspectRatio; a product's opinions override.
    void readBase(const usda::Prim& prim, StageRenderSettings& out) {
        if (auto cameras = targets(prim, "camera", "Camera"); !cameras.empty()) out.camera = cameras.front()->path;
        if (auto resolution = value(prim, "resolution", {"int2"})) {
            if (resolution->numbers.size() == 2 && resolution->numbers[0] >= 1 && resolution->numbers[1] >= 1 &&
                resolution->numbers[0] <= 65536 && resolution->numbers[1] <= 65536)
                out.resolution = std::array<int, 2>{int(resolution->numbers[0]), int(resolution->numbers[1])};
            else
                warn(prim, "resolution must be two sizes from 1 to 65536 pixels; ignored", prim.attribute("resolution")->where);
        }
        if (auto aspect = value(prim, "pixelAspectRatio", {"float", "double"})) {
            if (aspect->numbers.size() == 1 && aspect->numbers[0] > 0.0) out.pixelAspectRatio = aspect->numbers[0];
            else warn(prim, "pixelAspectRatio must be positive; ignored", prim.attribute("pixelAspectRatio")->where);
        }
        if (auto blur = value(prim, "disableMotionBlur", {"bool"})) out.disableMotionBlur = blur->numbers.front() != 0.0;
        if (auto dof = value(prim, "disableDepthOfField", {"bool"})) out.disableDepthOfField = dof->numbers.front() != 0.0;
        // The camera's aperture widens to the image's aspect (camera.cpp's "fit"): UsdRender's
        // expandAperture, its default.
        if (auto policy = value(prim, "aspectRatioConformPolicy", {"token"}); policy && policy->strings.front() != "expandAperture")
            warn(prim, "aspectRatioConformPolicy " + policy->strings.front() + " is not supported; expandAperture is used",
                 prim.attribute("aspectRatioConformPolicy")->where);
        if (auto window = value(prim, "dataWindowNDC", {"float4"});
            window && window->numbers != std::vector<double>{0.0, 0.0, 1.0, 1.0})
            warn(prim, "dataWindowNDC other than (0, 0, 1, 1) is not supported; the whole image is rendered",
                 prim.attribute("dataWindowNDC")->where);
    }

    void readProduct(const usda::Prim& product, StageRenderSettings& out) {
        readBase(product, out);
        if (auto name = value(product, "productName", {"token", "string"})) out.productName = name->strings.front();
        if (auto type = value(product, "productType", {"token"}); type && type->strings.front() != "raster")
            warn(product, "productType " + type->strings.front() + " is not rendered (only raster); its image is a raster",
                 product.attribute("productType")->where);
        for (const usda::Prim* var : targets(product, "orderedVars", "RenderVar")) {
            auto sourceName = value(*var, "sourceName", {"string", "token"});
            auto sourceType = value(*var, "sourceType", {"token"});
            // An unauthored sourceName is the schema's "": the var's own name is Hydra's fallback.
            std::string name = sourceName ? sourceName->strings.front() : var->name;
            std::string type = sourceType ? sourceType->strings.front() : "raw";
            auto aov = aovOfRenderVar(type, name);
            if (!aov) {
                warn(*var, "no AOV answers sourceName \"" + name + "\" of sourceType " + type + "; the var is not written",
                     var->where);
                continue;
            }
            if (std::find(out.aovs.begin(), out.aovs.end(), *aov) == out.aovs.end()) out.aovs.push_back(*aov);
        }
    }

    std::variant<std::vector<StageRenderSettings>, std::string> read(const std::string& path) {
        const usda::Prim* prim = stage_.find(path);
        if (!prim) return "render settings <" + path + "> do not exist";
        if (prim->typeName != "RenderSettings")
            return "<" + path + "> is a " + (prim->typeName.empty() ? "typeless prim" : prim->typeName) +
                   ", not a RenderSettings prim";
        StageRenderSettings out;
        out.path = path;
        readBase(*prim, out);
        if (auto purposes = value(*prim, "includedPurposes", {"token"}); purposes && purposes->isArray) {
            std::string list;
            for (const auto& purpose : purposes->strings) list += (list.empty() ? "" : ",") + purpose;
            out.includedPurposes = list;
        }
        auto products = targets(*prim, "products", "RenderProduct");
        if (products.empty()) return std::vector<StageRenderSettings>{out};
        std::vector<StageRenderSettings> each;
        for (const usda::Prim* product : products) {
            StageRenderSettings settings = out;
            readProduct(*product, settings);
            const bool repeated = std::any_of(each.begin(), each.end(), [&](const StageRenderSettings& other) {
                return !settings.productName.empty() && other.productName == settings.productName;
            });
            if (repeated) {
                warn(*product, "productName \"" + settings.productName + "\" is an earlier product's; not written twice",
                     product->where);
                continue;
            }
            each.push_back(std::move(settings));
        }
        return each;
    }

private:
    const usda::Stage& stage_;
    std::vector<HostMessage>& messages_;
};

}  // namespace

std::variant<std::vector<StageRenderSettings>, std::string> readStageRenderSettings(const usda::Stage& stage,
                                                                                    const std::string& path,
                                                                                    std::vector<HostMessage>& messages) {
    return Reader(stage, messages).read(path);
}

}  // namespace obscura::harness
