#include "renderer/render_settings.h"

#include "passes/depth_of_field.h"
#include "passes/motion_blur.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string_view>
#include <type_traits>

namespace obscura::renderer {
namespace {

// A setting that is its FrameSettings member's value (a bool is on where the value is not 0).
template <auto Member>
void number(FrameSettings& settings, double value, const std::string&) {
    using T = std::remove_reference_t<decltype(settings.*Member)>;
    settings.*Member = static_cast<T>(value);
}
template <auto Member>
void token(FrameSettings& settings, double, const std::string& value) {
    settings.*Member = value;
}

const RenderSettingInfo kSettings[] = {
    {"exposure", number<&FrameSettings::exposureStops>,
     "exposure adjustment in stops, added to the camera's exposure (float, default 0)",
     OBSCURA_VALUE_FLOAT, 0.0},
    {"refineLevel", number<&FrameSettings::refineLevel>,
     "subdivision level of catmullClark/loop/bilinear meshes, 0-6; a mesh's obscura:refineLevel "
     "overrides it (int, default 2)",
     OBSCURA_VALUE_INT, 2.0},
    {"ssao", number<&FrameSettings::ssao>,
     "screen-space ambient occlusion on environment light (bool, default on)", OBSCURA_VALUE_BOOL, 1.0},
    {"ssao:radius", number<&FrameSettings::ssaoRadiusMetres>,
     "ambient occlusion radius in metres (float, default 0.5)", OBSCURA_VALUE_FLOAT, 0.5},
    {"ssao:intensity", number<&FrameSettings::ssaoIntensity>,
     "ambient occlusion strength, 0-1 (float, default 1)", OBSCURA_VALUE_FLOAT, 1.0},
    {"lighting:halfFloat", [](FrameSettings& s, double v, const std::string&) {
         s.lightAccumulation = v != 0.0 ? passes::LightAccumulation::HalfFloat : passes::LightAccumulation::SmallFloat;
     },
     "accumulate lighting in RGBA16F instead of B10G11R11_UFLOAT: about 2^-11 relative "
     "precision instead of 2^-7..2^-6, twice the bandwidth; frames of temporal AA 1TX (a still's) "
     "and the reference's sub-frames always do (bool, default off)",
     OBSCURA_VALUE_BOOL, 0.0},
    {"transparents:fadeDistance", number<&FrameSettings::transparentFadeMetres>,
     "soft intersections of transparent surfaces (opacity below 1): a surface fades "
     "out over this distance in metres in front of the opaque surface behind it; 0 "
     "keeps the intersection hard (float, default 0)",
     OBSCURA_VALUE_FLOAT, 0.0, 0.0},
    {"shadows", number<&FrameSettings::shadows>,
     "shadow maps: cascaded for distant lights, cube maps (or one spot map inside a ShapingAPI cone) "
     "for sphere, rect and disk lights, for every light whose inputs:shadow:enable is on "
     "(bool, default on)",
     OBSCURA_VALUE_BOOL, 1.0},
    {"shadows:resolution", number<&FrameSettings::shadowResolution>,
     "side of one shadow map (a cascade, a cube face, a spot map) in texels, 64-4096 "
     "(int, default 1024)",
     OBSCURA_VALUE_INT, 1024.0, 64.0, 4096.0},
    {"shadows:cascades", number<&FrameSettings::shadowCascades>,
     "cascades per distant light, 1-4 (int, default 4)", OBSCURA_VALUE_INT, 4.0, 1.0, 4.0},
    {"msaa", number<&FrameSettings::msaaSamples>,
     "samples per pixel of the G-buffer, 1, 2, 4 or 8 as the device offers (lavapipe: 1 and 4; another "
     "count is refused with the ones offered). Above 1: deferred MSAA (seed 000): a custom resolve copies "
     "sample 0 for the per-pixel passes and tags pixels whose samples differ (id, depth, normal) in stencil "
     "bit 0x80; lighting runs per sample there, resolved with tone-mapped weights 1/(1 + luma) so bright "
     "edges keep their coverage; a still's frames resolve linearly, under the box pixel filter each "
     "sample into the pixel whose box holds it. Reference mode renders 1 (int, default 1)",
     OBSCURA_VALUE_INT, 1.0, 1.0, 8.0},
    {"msaa:alphaToCoverage", number<&FrameSettings::msaaAlphaToCoverage>,
     "with msaa above 1, cut-out materials (opacityThreshold) cover the fraction of a "
     "pixel's samples their opacity gives, from one lookup (alpha-to-coverage), instead of "
     "testing the opacity at every sample's position (alpha-test supersampling, the "
     "default) (bool, default off)",
     OBSCURA_VALUE_BOOL, 0.0},
    {"taa", number<&FrameSettings::temporalAa>,
     "temporal anti-aliasing (seed 000 SMAA 1TX): the projection jitters by a sub-pixel offset each frame and "
     "an accumulation buffer, reprojected and clamped to the current frame's neighbourhood, gathers the "
     "offsets; a still image accumulates taa:frames frames, then renders once through the pixel centres and "
     "reports converged (bool, default on)",
     OBSCURA_VALUE_BOOL, 1.0},
    {"taa:frames", number<&FrameSettings::temporalAaFrames>,
     "frames a still image accumulates (1TX): the jitter cycles through this many offsets of "
     "Sobol's (0, 2)-sequence, each weighted equally; with motion blur each also samples its own "
     "1/taa:frames of the shutter, as reference sub-frames do, blurred over that part alone; with "
     "depth of field each looks through its own 1/taa:frames of the aperture, its post-process "
     "spreading it over that part alone; "
     "`obscura render` renders until converged, 1-1024 (int, default 16)",
     OBSCURA_VALUE_INT, 16.0, 1.0, 1024.0},
    {"taa:mode", [](FrameSettings& s, double, const std::string& t) {
         s.temporalAaMode = t == "2tx" ? passes::TemporalAaMode::Smaa2tx : passes::TemporalAaMode::Smaa1tx;
     },
     "1tx: SMAA 1TX accumulation with neighbourhood clamp; 2tx: SMAA 2TX, two frames (2x jitter) "
     "blended by velocity, no clamp (token, default 1tx)",
     OBSCURA_VALUE_TOKEN, 0.0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
     "1tx|2tx"},
    {"taa:kLowFreq", number<&FrameSettings::temporalAaKLowFreq>,
     "SMAA 1TX K_lowfreq: while the scene changes, where a pixel matches its neighbours the history "
     "weighs 1 / K (1 keeps the clamped history alone), at least 1 (float, default 2)",
     OBSCURA_VALUE_FLOAT, 2.0, 1.0},
    {"taa:kHighFreq", number<&FrameSettings::temporalAaKHighFreq>,
     "SMAA 1TX K_hifreq: the same where a pixel differs from its neighbours by 1 or more (edges); "
     "lower keeps edges anti-aliased in motion, higher keeps them sharper, at least 1 "
     "(float, default 1.25)",
     OBSCURA_VALUE_FLOAT, 1.25, 1.0},
    {"taa:reuseConverged", number<&FrameSettings::temporalAaReuseConverged>,
     "renders of a converged still (1tx) keep its colour without lighting the frame again: they "
     "draw the G-buffer for the unjittered depth, normal and id AOVs and, where no transparent "
     "surface is drawn (its coverage reaches the AOVs), leave out the lighting, which only the colour "
     "reads; off, each such render runs the whole frame "
     "(`obscura bench` turns it off to time whole frames) (bool, default on)",
     OBSCURA_VALUE_BOOL, 1.0},
    {"taa:hybridDistance", number<&FrameSettings::hybridAaDistanceMetres>,
     "hybrid AA (seed 004), 1tx only: objects whose bounds come nearer the camera than this "
     "many metres are drawn without the jitter and anti-aliased by edge AA (morphological, "
     "after temporal AA) instead of accumulated, where view-dependent shading changes fastest "
     "as the camera moves; farther ones stay temporal; 0 makes every object temporal "
     "(float, default 0)",
     OBSCURA_VALUE_FLOAT, 0.0, 0.0},
    {"domeLightCameraVisibility", number<&FrameSettings::domeLightCameraVisibility>,
     "dome lights are seen by the camera where nothing is drawn, as Hydra's setting of the "
     "name: their texture (or colour) times intensity is the background, which is then "
     "opaque (the colour AOV's alpha is 1); off: the background is black and transparent "
     "(bool, default on)",
     OBSCURA_VALUE_BOOL, 1.0},
    {"metersPerUnit", number<&FrameSettings::metersPerUnit>,
     "the scene's metres per unit, as USD's stage metadata; hosts set it (float, default 0.01)",
     OBSCURA_VALUE_FLOAT, 0.01},
    {"timeCodesPerSecond", number<&FrameSettings::timeCodesPerSecond>,
     "the scene's time codes per second, as USD's stage metadata, for points and instances "
     "moved by their velocities within the shutter; hosts set it (float, default 24)",
     OBSCURA_VALUE_FLOAT, 24.0, 1e-6},
    {"dof", number<&FrameSettings::depthOfField>,
     "depth of field from the camera's lens (focalLength, fStop, focusDistance, obscura:apertureBlades, "
     "obscura:apertureRotation): a real-time frame is seen through the lens's centre and blurred by the "
     "post-process over the whole aperture (seed 000); a still's accumulated frames (taa:frames) each look "
     "through their own part of the aperture and are blurred over it alone, converging to the lens's "
     "integral; a camera with fStop 0 has none (bool, default on)",
     OBSCURA_VALUE_BOOL, 1.0},
    {"dof:taps", number<&FrameSettings::depthOfFieldTaps>,
     "taps per side of the depth of field's first gather pass (N x N taps; larger blurs reach further "
     "and look smoother at a higher cost), 3-15 (int, default 7)",
     OBSCURA_VALUE_INT, double(passes::kDefaultDofTapsPerSide), double(passes::kMinDofTapsPerSide),
     double(passes::kMaxDofTapsPerSide)},
    {"motionBlur", number<&FrameSettings::motionBlur>,
     "motion blur over the camera's shutter (shutter:open to shutter:close, in time codes): a "
     "real-time frame is seen at the shutter's centre and blurred along the screen-space motion of the "
     "camera and of moving prims (McGuire 2012's reconstruction filter, separable, streaks up to half "
     "the image); a still's accumulated frames (taa:frames) each sample their own part of the shutter "
     "and are blurred over it alone, converging to the shutter's integral; a camera whose shutter is "
     "closed (open = close) has none (bool, default on)",
     OBSCURA_VALUE_BOOL, 1.0},
    {"motionBlur:samples", number<&FrameSettings::motionBlurSamples>,
     "taps per motion blur gather pass; the two passes place samples^2 along a blur (more is "
     "smoother and slower), 2-32 (int, default 8)",
     OBSCURA_VALUE_INT, 8.0, double(passes::kMinMotionBlurSamples), double(passes::kMaxMotionBlurSamples)},
    {"reference", number<&FrameSettings::referenceSubFrames>,
     "ground truth: average this many sub-frames, each seen from a point of the lens aperture, at a time "
     "within the shutter and a sub-pixel offset, with post-process depth of field and motion blur off "
     "(the dof and motionBlur settings still decide whether the lens and the shutter are sampled); 0 "
     "renders the normal frame (int, default 0)",
     OBSCURA_VALUE_INT, 0.0, 0.0, 65536.0},
    {"pixelFilter", [](FrameSettings& s, double, const std::string& t) { s.pixelFilter.kind = pixelFilterKind(t); },
     "the pixel filter of a still (and of the reference): its accumulated frames take their sub-pixel "
     "offsets distributed as the filter (importance sampling, as offline renderers draw film "
     "samples), so their mean is the filtered image: box (the pixel's square at width 1), gaussian "
     "(standard deviation width / 12) or blackman-harris (4-term, over the width), as Cycles "
     "defines them; a changing scene's frames keep temporal AA's jitter within the pixel "
     "(token, default box)",
     OBSCURA_VALUE_TOKEN, 0.0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
     "box|gaussian|blackman-harris", "box"},
    {"pixelFilter:width", [](FrameSettings& s, double v, const std::string&) { s.pixelFilter.width = v; },
     "the pixel filter's support in pixels, 0.25-8 (float, default 1)", OBSCURA_VALUE_FLOAT, 1.0,
     0.25, 8.0},
    {"pixelAspectRatio", number<&FrameSettings::pixelAspectRatio>,
     "a pixel's width over its height, as UsdRenderSettings' pixelAspectRatio: the camera's "
     "aperture is conformed to an image width x pixelAspectRatio wide, 0.01-100 (float, default 1)",
     OBSCURA_VALUE_FLOAT, 1.0, 0.01, 100.0},
    {"includedPurposes", token<&FrameSettings::includedPurposes>,
     "the purposes drawn, comma-separated from default, render, proxy and guide (Hydra's "
     "render tags; a prim's purpose is UsdGeomImageable's computed purpose): a stage's proxies "
     "and guides are left out unless named (token, default default,render)",
     OBSCURA_VALUE_TOKEN, 0.0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
     "default|render|proxy|guide", "default,render", true},
    {"ocio:config", token<&FrameSettings::ocioConfig>,
     "OpenColorIO config file (token; default: $OCIO, else the built-in ACES-based config)",
     OBSCURA_VALUE_TOKEN, 0.0},
    {"ocio:display", token<&FrameSettings::ocioDisplay>,
     "OCIO display (token; default: the config's default display)", OBSCURA_VALUE_TOKEN, 0.0},
    {"ocio:view", token<&FrameSettings::ocioView>,
     "OCIO view (token; default: the display's default view, Filmic in the built-in config)",
     OBSCURA_VALUE_TOKEN, 0.0},
    {"ocio:look", token<&FrameSettings::ocioLook>,
     "OCIO looks, comma-separated, replacing the view's own (token; default: none)",
     OBSCURA_VALUE_TOKEN, 0.0},
    {"grading:chart", token<&FrameSettings::gradingChart>,
     "an image whose top-left corner holds a colour-grading chart (obscura grade-chart --write "
     "makes the neutral one; grade it, or a screenshot holding it, in any image editor): the 16^3 "
     "LUT read from it grades the display values after the OCIO view (token; default: none)",
     OBSCURA_VALUE_TOKEN, 0.0},
    {"grading:interpolation", [](FrameSettings& s, double, const std::string& t) {
         s.gradingInterpolation = t == "tetrahedral" ? passes::LatticeInterpolation::Tetrahedral
                                                   : passes::LatticeInterpolation::Trilinear;
     },
     "between the grading chart's lattice points: trilinear (seed 004's hardware "
     "filter) or tetrahedral (keeps neutral greys neutral) (token, default trilinear)",
     OBSCURA_VALUE_TOKEN, 0.0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
     "trilinear|tetrahedral"},
    {"textures:compression", number<&FrameSettings::textureCompression>,
     "block-compressed material textures where the device samples the format: 8-bit colour as BC1 "
     "(opaque) or BC3 (with alpha), 8-bit tangent-space normal maps read as 2 n - 1 from raw files as "
     "BC5 (two channels, z reconstructed); off keeps 8-bit textures RGBA8 (bool, default on)",
     OBSCURA_VALUE_BOOL, 1.0},
    {"occlusionCulling", number<&FrameSettings::occlusionCulling>,
     "occlusion culling (seed 004): what the camera's depth hides is not drawn by the camera, tested "
     "as occlusionCulling:route says (bool, default off)",
     OBSCURA_VALUE_BOOL, 0.0},
    {"occlusionCulling:route", [](FrameSettings& s, double, const std::string& t) {
         s.occlusionCullingRoute =
             t == "coverageBuffer" ? OcclusionCullingRoute::CoverageBuffer : OcclusionCullingRoute::Gpu;
     },
     "gpu: in two phases within the frame, on the GPU: what the last frame saw is drawn first, a "
     "depth pyramid is built from it, every instance's bounds are tested against it by a compute pass "
     "that writes indirect draws, and what else is visible is drawn then; it never leaves out what "
     "the frame shows, and culls the shadow views the same way against their own depth. "
     "coverageBuffer: the talk's coverage buffer, the last frame's depth reduced to "
     "8x8-pixel tiles, read back after its fence, reprojected on the CPU into this frame's view; a "
     "camera cut, the first frame or a change to what is drawn tests nothing, and a sub-pixel gap no "
     "sample of the last frame saw through is taken as covered, and the shadow maps draw every "
     "caster (docs/ARCHITECTURE.md) (token, default gpu)",
     OBSCURA_VALUE_TOKEN, 0.0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
     "gpu|coverageBuffer", "gpu"},
};

bool isTokenChoice(std::string_view choices, std::string_view token) {
    for (size_t start = 0;;) {
        size_t end = choices.find('|', start);
        if (choices.substr(start, end - start) == token) return true;
        if (end == std::string_view::npos) return false;
        start = end + 1;
    }
}

// Why `token` is not a value of the setting, or "".
std::string tokenProblem(const RenderSettingInfo& info, std::string_view token) {
    if (!info.tokenChoices) return {};
    if (!info.tokenList)
        return isTokenChoice(info.tokenChoices, token)
                   ? std::string()
                   : "'" + std::string(token) + "' is not one of " + info.tokenChoices;
    for (size_t start = 0; start <= token.size();) {
        size_t end = std::min(token.find(',', start), token.size());
        std::string_view entry = token.substr(start, end - start);
        if (!isTokenChoice(info.tokenChoices, entry))
            return "'" + std::string(entry) + "' in '" + std::string(token) + "' is not one of " + info.tokenChoices;
        start = end + 1;
    }
    return {};
}

}  // namespace

const RenderSettingInfo* findRenderSetting(const std::string& name) {
    for (const auto& s : kSettings)
        if (name == s.name) return &s;
    return nullptr;
}

const RenderSettingInfo* renderSettingAt(uint32_t index) {
    return index < std::size(kSettings) ? &kSettings[index] : nullptr;
}

FrameSettings::FrameSettings() {
    for (const auto& info : kSettings) info.apply(*this, info.defaultNumber, info.defaultToken ? info.defaultToken : "");
}

std::string RenderSettings::set(const std::string& name, const ObscuraValue* value) {
    const RenderSettingInfo* info = findRenderSetting(name);
    if (!info) return "unknown render setting '" + name + "' (see `obscura info`)";
    if (!value) {
        info->apply(values_, info->defaultNumber, info->defaultToken ? info->defaultToken : "");
        ++version_;
        return {};
    }
    if (value->isArray || value->count != 1 || !value->data) return name + ": expected one value";
    if (info->type == OBSCURA_VALUE_TOKEN) {
        const char* const* text = static_cast<const char* const*>(value->data);
        if (value->type != OBSCURA_VALUE_TOKEN || !text[0]) return name + ": expected a token";
        if (std::string problem = tokenProblem(*info, text[0]); !problem.empty()) return name + ": " + problem;
        info->apply(values_, 0.0, text[0]);
        ++version_;
        return {};
    }
    double v = 0;
    switch (value->type) {
        case OBSCURA_VALUE_FLOAT: v = *static_cast<const float*>(value->data); break;
        case OBSCURA_VALUE_DOUBLE: v = *static_cast<const double*>(value->data); break;
        case OBSCURA_VALUE_INT:
        case OBSCURA_VALUE_BOOL: v = *static_cast<const int32_t*>(value->data); break;
        default: return name + ": expected a number";
    }
    if (!std::isfinite(v)) return name + ": value is not finite";
    if (info->type == OBSCURA_VALUE_INT && v != std::floor(v)) return name + ": expected a whole number";
    if (v < info->minimum || v > info->maximum) {
        char range[96];
        std::snprintf(range, sizeof(range), "%g is outside %g..%g", v, info->minimum, info->maximum);
        return name + ": " + range;
    }
    info->apply(values_, v, {});
    ++version_;
    return {};
}

}  // namespace obscura::renderer
