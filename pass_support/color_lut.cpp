// Seed 004 "Color grading" / Selan 2007: the display/view transform evaluated once on a lattice by
// OpenColorIO's CPU processor, then looked up per pixel on the GPU.
#include "pass_support/color_lut.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <numbers>

namespace OCIO = OCIO_NAMESPACE;

namespace obscura::passes {
namespace {

// ---- Shaper -------------------------------------------------------------------------------

struct ShaperToe {
    float range;       // R = max - min stops
    float linear;      // xToe, where the toe touches the log segment
    float coordinate;  // cToe = c(xToe)
};

ShaperToe shaperToe(const ColorLut& lut) {
    const float range = lut.shaperMaxStops - lut.shaperMinStops;
    const float invLn2 = std::numbers::log2e_v<float>;
    return {range, kShaperMiddleGrey * std::exp2(lut.shaperMinStops + invLn2), invLn2 / range};
}

// ---- The built-in config ------------------------------------------------------------------

OCIO::TransformRcPtr builtin(const char* style, OCIO::TransformDirection direction = OCIO::TRANSFORM_DIR_FORWARD) {
    OCIO::BuiltinTransformRcPtr transform = OCIO::BuiltinTransform::Create();
    transform->setStyle(style);
    transform->setDirection(direction);
    return transform;
}

OCIO::TransformRcPtr group(std::initializer_list<OCIO::TransformRcPtr> transforms) {
    OCIO::GroupTransformRcPtr result = OCIO::GroupTransform::Create();
    for (const OCIO::TransformRcPtr& transform : transforms) result->appendTransform(transform);
    return result;
}

OCIO::ColorSpaceRcPtr colorSpace(const char* name, OCIO::ReferenceSpaceType reference, const char* description) {
    OCIO::ColorSpaceRcPtr space = OCIO::ColorSpace::Create(reference);
    space->setName(name);
    space->setDescription(description);
    return space;
}

// Mirrors the ACES studio configs: ACES2065-1 is the scene reference and CIE XYZ (D65) the
// display reference, so each view transform is one ACES built-in.
OCIO::ConstConfigRcPtr makeBuiltInConfig() {
    OCIO::ConfigRcPtr config = OCIO::Config::Create();
    config->setName("Obscura built-in (ACES 1.0 SDR video)");

    config->addColorSpace(colorSpace("ACES2065-1", OCIO::REFERENCE_SPACE_SCENE, "The scene reference space"));

    // Linear Rec.709 has no direct ACES built-in: go through AP1 (ACEScg), whose built-ins carry
    // the Bradford D65 <-> ACES-white adaptation.
    OCIO::ColorSpaceRcPtr linearRec709 =
        colorSpace("Linear Rec.709 (sRGB)", OCIO::REFERENCE_SPACE_SCENE, "Scene-linear, sRGB/Rec.709 primaries");
    linearRec709->setTransform(group({builtin("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD", OCIO::TRANSFORM_DIR_INVERSE),
                                      builtin("ACEScg_to_ACES2065-1")}),
                               OCIO::COLORSPACE_DIR_TO_REFERENCE);
    config->addColorSpace(linearRec709);

    OCIO::ColorSpaceRcPtr raw = colorSpace("Raw", OCIO::REFERENCE_SPACE_SCENE, "Data: never converted");
    raw->setIsData(true);
    config->addColorSpace(raw);

    // No clamp here: the display's [0,1] clamp belongs after the LUT's interpolation (color_lut.h).
    OCIO::ColorSpaceRcPtr srgbDisplay =
        colorSpace("sRGB - Display", OCIO::REFERENCE_SPACE_DISPLAY, "sRGB primaries, piecewise sRGB encoding");
    srgbDisplay->setTransform(builtin("DISPLAY - CIE-XYZ-D65_to_sRGB"), OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(srgbDisplay);

    OCIO::ViewTransformRcPtr filmic = OCIO::ViewTransform::Create(OCIO::REFERENCE_SPACE_SCENE);
    filmic->setName("ACES 1.0 - SDR Video");
    filmic->setDescription("ACES Reference Rendering Transform with the SDR video (100 nit) output transform");
    filmic->setTransform(builtin("ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0"),
                         OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE);
    config->addViewTransform(filmic);

    OCIO::ViewTransformRcPtr untoned = OCIO::ViewTransform::Create(OCIO::REFERENCE_SPACE_SCENE);
    untoned->setName("Un-tone-mapped");
    untoned->setDescription("Scene values shown as display values: a change of primaries only");
    untoned->setTransform(builtin("UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"), OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE);
    config->addViewTransform(untoned);

    config->addDisplayView("sRGB", "Filmic", "ACES 1.0 - SDR Video", "sRGB - Display", "", "", "");
    config->addDisplayView("sRGB", "Standard", "Un-tone-mapped", "sRGB - Display", "", "", "");
    config->addDisplayView("sRGB", "Raw", "Raw", "");

    config->setRole(OCIO::ROLE_SCENE_LINEAR, "Linear Rec.709 (sRGB)");
    config->setRole(OCIO::ROLE_DEFAULT, "Linear Rec.709 (sRGB)");
    config->setRole(OCIO::ROLE_DATA, "Raw");
    config->setRole("aces_interchange", "ACES2065-1");
    config->validate();
    return config;
}

// ---- Loading and caching ------------------------------------------------------------------

struct LoadedConfig {
    OCIO::ConstConfigRcPtr config;
    std::string label;  // for descriptions and errors
};

struct ResolvedView {
    OCIO::ConstCPUProcessorRcPtr processor;
    std::string description;
};

// Configs are cached per path and processors per (path, display, view, look): a file edited on
// disk during the process is not re-read.
struct Cache {
    std::mutex mutex;
    std::map<std::string, LoadedConfig> configs;
    std::map<std::string, ResolvedView> views;
};

Cache& cache() {
    static Cache instance;
    return instance;
}

std::string joinNames(const std::vector<std::string>& names) {
    if (names.empty()) return "(none)";
    std::string joined;
    for (const std::string& name : names) joined += (joined.empty() ? "" : ", ") + name;
    return joined;
}

std::string resolveConfigPath(const std::string& requested) {
    if (!requested.empty()) return requested;
    const char* environment = std::getenv("OCIO");
    return environment ? environment : "";
}

// Throws OCIO::Exception; the caller holds the cache lock.
std::variant<LoadedConfig, std::string> loadConfig(const std::string& path) {
    if (auto it = cache().configs.find(path); it != cache().configs.end()) return it->second;
    LoadedConfig loaded;
    if (path.empty()) {
        loaded = {makeBuiltInConfig(), "built-in"};
    } else {
        std::error_code error;
        if (!std::filesystem::is_regular_file(path, error)) return "OCIO config file not found: '" + path + "'";
        loaded.config = OCIO::Config::CreateFromFile(path.c_str());
        loaded.label = *loaded.config->getName() ? loaded.config->getName() : path;
    }
    cache().configs.emplace(path, loaded);
    return loaded;
}

std::vector<std::string> displays(const OCIO::Config& config) {
    std::vector<std::string> names;
    for (int i = 0; i < config.getNumDisplays(); ++i) names.emplace_back(config.getDisplay(i));
    return names;
}

std::vector<std::string> views(const OCIO::Config& config, const std::string& display) {
    std::vector<std::string> names;
    for (int i = 0; i < config.getNumViews(display.c_str()); ++i)
        names.emplace_back(config.getView(display.c_str(), i));
    return names;
}

std::vector<std::string> looks(const OCIO::Config& config) {
    std::vector<std::string> names;
    for (int i = 0; i < config.getNumLooks(); ++i) names.emplace_back(config.getLookNameByIndex(i));
    return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

// The look names in OCIO's look syntax: ',' or ':' between looks, '|' between alternatives, an
// optional '+' or '-' (inverse) prefix on each.
std::vector<std::string> lookNamesIn(const std::string& lookList) {
    std::vector<std::string> names;
    std::string current;
    auto flush = [&] {
        const size_t first = current.find_first_not_of(" \t+-");
        const size_t last = current.find_last_not_of(" \t");
        if (first != std::string::npos) names.push_back(current.substr(first, last - first + 1));
        current.clear();
    };
    for (char c : lookList) {
        if (c == ',' || c == ':' || c == '|') flush();
        else current += c;
    }
    flush();
    return names;
}

// Checks the names up front so that errors list the valid choices (OCIO's own messages do not).
std::variant<ResolvedView, std::string> resolveView(const LoadedConfig& loaded, const ColorLutRequest& request) {
    const OCIO::Config& config = *loaded.config;
    const std::string display = request.display.empty() ? config.getDefaultDisplay() : request.display;
    if (!contains(displays(config), display))
        return "display '" + display + "' not found in config " + loaded.label + "; valid displays: " +
               joinNames(displays(config));
    const std::string view = request.view.empty() ? config.getDefaultView(display.c_str()) : request.view;
    if (!contains(views(config, display), view))
        return "view '" + view + "' not found for display '" + display + "' in config " + loaded.label +
               "; valid views: " + joinNames(views(config, display));
    for (const std::string& look : lookNamesIn(request.look))
        if (!config.getLook(look.c_str()))
            return "look '" + look + "' not found in config " + loaded.label +
                   "; valid looks: " + joinNames(looks(config));

    OCIO::DisplayViewTransformRcPtr displayView = OCIO::DisplayViewTransform::Create();
    displayView->setSrc(OCIO::ROLE_SCENE_LINEAR);
    displayView->setDisplay(display.c_str());
    displayView->setView(view.c_str());
    // The legacy pipeline is OCIO's way to override a view's looks (as ociodisplay does).
    OCIO::LegacyViewingPipelineRcPtr pipeline = OCIO::LegacyViewingPipeline::Create();
    pipeline->setDisplayViewTransform(displayView);
    if (!request.look.empty()) {
        pipeline->setLooksOverrideEnabled(true);
        pipeline->setLooksOverride(request.look.c_str());
    }
    // Lossless: the default optimisation approximates log/exp/pow, and this processor is also the
    // reference the LUT is tested against.
    OCIO::ConstCPUProcessorRcPtr processor = pipeline->getProcessor(loaded.config)->getOptimizedCPUProcessor(
        OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32, OCIO::OPTIMIZATION_LOSSLESS);
    const std::string viewLooks = config.getDisplayViewLooks(display.c_str(), view.c_str());
    const std::string appliedLooks = request.look.empty() ? viewLooks : request.look;
    return ResolvedView{processor, "config: " + loaded.label + ", display: " + display + ", view: " + view +
                                       ", look: " + (appliedLooks.empty() ? "none" : appliedLooks)};
}

std::variant<ResolvedView, std::string> cachedView(const ColorLutRequest& request) {
    const std::string path = resolveConfigPath(request.configPath);
    const std::string key = path + '\n' + request.display + '\n' + request.view + '\n' + request.look;
    std::lock_guard lock(cache().mutex);
    if (auto it = cache().views.find(key); it != cache().views.end()) return it->second;
    try {
        std::variant<LoadedConfig, std::string> loaded = loadConfig(path);
        if (auto* error = std::get_if<std::string>(&loaded))
            return *error + (request.configPath.empty() ? " (from $OCIO)" : "");
        std::variant<ResolvedView, std::string> resolved = resolveView(std::get<LoadedConfig>(loaded), request);
        if (auto* view = std::get_if<ResolvedView>(&resolved)) cache().views.emplace(key, *view);
        return resolved;
    } catch (const OCIO::Exception& exception) {
        return std::string("OpenColorIO: ") + exception.what() + (path.empty() ? "" : " (config '" + path + "')");
    }
}

}  // namespace

float shaperEncode(float linear, const ColorLut& lut) {
    const ShaperToe toe = shaperToe(lut);
    const float coordinate = linear < toe.linear
                                 ? linear * (toe.coordinate / toe.linear)
                                 : (std::log2(linear / kShaperMiddleGrey) - lut.shaperMinStops) / toe.range;
    return std::clamp(coordinate, 0.0f, 1.0f);
}

float shaperDecode(float coordinate, const ColorLut& lut) {
    const ShaperToe toe = shaperToe(lut);
    return coordinate < toe.coordinate ? coordinate * (toe.linear / toe.coordinate)
                                       : kShaperMiddleGrey * std::exp2(coordinate * toe.range + lut.shaperMinStops);
}

std::variant<ColorLut, std::string> bakeColorLut(const ColorLutRequest& request, uint32_t size) {
    if (size < 2) return "a 3D LUT needs at least 2 lattice points per axis, got " + std::to_string(size);
    std::variant<ResolvedView, std::string> resolved = cachedView(request);
    if (auto* error = std::get_if<std::string>(&resolved)) return *error;
    const ResolvedView& view = std::get<ResolvedView>(resolved);

    ColorLut lut;
    lut.size = size;
    lut.description = view.description;
    std::vector<float> axis(size);
    for (uint32_t i = 0; i < size; ++i) axis[i] = shaperDecode(float(i) / float(size - 1), lut);

    lut.rgba.resize(size_t(size) * size * size * 4);
    float* texel = lut.rgba.data();
    for (uint32_t b = 0; b < size; ++b)
        for (uint32_t g = 0; g < size; ++g)
            for (uint32_t r = 0; r < size; ++r, texel += 4) {
                texel[0] = axis[r];
                texel[1] = axis[g];
                texel[2] = axis[b];
                texel[3] = 1.0f;
            }
    try {
        OCIO::PackedImageDesc image(lut.rgba.data(), long(size) * size * size, 1, 4);
        view.processor->apply(image);
    } catch (const OCIO::Exception& exception) {
        return std::string("OpenColorIO: ") + exception.what();
    }
    return lut;
}

std::variant<std::array<float, 3>, std::string> applyViewTransform(const ColorLutRequest& request,
                                                                   std::array<float, 3> linearRgb) {
    std::variant<ResolvedView, std::string> resolved = cachedView(request);
    if (auto* error = std::get_if<std::string>(&resolved)) return *error;
    try {
        std::get<ResolvedView>(resolved).processor->applyRGB(linearRgb.data());
    } catch (const OCIO::Exception& exception) {
        return std::string("OpenColorIO: ") + exception.what();
    }
    return linearRgb;
}

std::vector<std::string> builtInViews() {
    std::lock_guard lock(cache().mutex);
    try {
        std::variant<LoadedConfig, std::string> loaded = loadConfig("");
        return views(*std::get<LoadedConfig>(loaded).config, "sRGB");
    } catch (const OCIO::Exception&) {
        return {};
    }
}

}  // namespace obscura::passes
