// Render settings by name, as DESIGN.md names them everywhere (ABI, --set, docs): one table gives
// each setting its type, range, default and description, and how it fills FrameSettings, the typed
// values the delegate and the frame read. A value is parsed and checked once, when it is set; no
// frame reads a setting by its name. Only settings the frame honours are listed; `obscura info`
// prints this table.
#pragma once

#include "pass_support/grading_lattice.h"
#include "passes/lighting.h"
#include "passes/temporal_aa.h"
#include "renderer/pixel_filter.h"

#include <obscura/obscura.h>

#include <cstdint>
#include <limits>
#include <map>
#include <string>

namespace obscura::renderer {

// Where occlusion culling tests (render setting occlusionCulling:route).
enum class OcclusionCullingRoute {
    Gpu,             // this frame's early depth, on the GPU (passes/occlusion_cull.h)
    CoverageBuffer,  // the last frame's depth, reprojected on the CPU (renderer/coverage_buffer.h)
};

// Every setting's current value, typed, in the units the frame works in unless the name says
// otherwise. Default-constructed it holds each setting's default from the table.
struct FrameSettings {
    FrameSettings();

    double exposureStops;
    int32_t refineLevel;
    bool ssao;
    double ssaoRadiusMetres;
    double ssaoIntensity;
    passes::LightAccumulation lightAccumulation;
    double transparentFadeMetres;
    bool shadows;
    uint32_t shadowResolution;
    uint32_t shadowCascades;
    uint32_t msaaSamples;
    bool msaaAlphaToCoverage;
    bool temporalAa;
    uint32_t temporalAaFrames;
    passes::TemporalAaMode temporalAaMode;
    float temporalAaKLowFreq;
    float temporalAaKHighFreq;
    bool temporalAaReuseConverged;
    double hybridAaDistanceMetres;
    bool domeLightCameraVisibility;
    double metersPerUnit;
    double timeCodesPerSecond;
    bool depthOfField;
    int32_t depthOfFieldTaps;
    bool motionBlur;
    int32_t motionBlurSamples;
    uint32_t referenceSubFrames;
    PixelFilter pixelFilter;
    double pixelAspectRatio;
    std::string includedPurposes;  // comma-separated (delegate/purposes.h)
    std::string ocioConfig, ocioDisplay, ocioView, ocioLook;
    std::string gradingChart;
    passes::LatticeInterpolation gradingInterpolation;
    bool textureCompression;
    bool occlusionCulling;
    OcclusionCullingRoute occlusionCullingRoute;
};

struct RenderSettingInfo {
    const char* name;
    // Stores a checked value (the number, or the token) into its FrameSettings member.
    void (*apply)(FrameSettings&, double number, const std::string& token);
    const char* description;
    ObscuraValueType type;
    double defaultNumber;
    // Numbers outside [minimum, maximum] are refused with a reason (none given: any finite value).
    double minimum = -std::numeric_limits<double>::infinity();
    double maximum = std::numeric_limits<double>::infinity();
    // Tokens: the accepted values, '|'-separated (none given: any token).
    const char* tokenChoices = nullptr;
    // Tokens: the value when unset (none given: "").
    const char* defaultToken = nullptr;
    // Tokens: a comma-separated list, each entry one of tokenChoices.
    bool tokenList = false;
};

const RenderSettingInfo* findRenderSetting(const std::string& name);
const RenderSettingInfo* renderSettingAt(uint32_t index);

class RenderSettings {
public:
    // Stores a value after checking its type and range; returns a reason on failure (the value
    // stays as it was). nullptr resets the setting to its default.
    std::string set(const std::string& name, const ObscuraValue* value);
    const FrameSettings& values() const { return values_; }
    // Counts every change: what was rendered with other settings is not reused.
    uint64_t version() const { return version_; }

private:
    FrameSettings values_;
    uint64_t version_ = 0;
};

}  // namespace obscura::renderer
