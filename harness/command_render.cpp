#include "harness/aov_output.h"
#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/frame_output.h"
#include "harness/session.h"
#include "harness/usd_render_settings.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace obscura::harness {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::variant<std::vector<double>, std::string> frameList(const RenderOptions& o, const usda::StageMetadata& meta) {
    if (!o.frames.empty()) {
        auto dash = o.frames.find('-', 1);
        char* end = nullptr;
        double a = std::strtod(o.frames.c_str(), &end);
        double b = dash == std::string::npos ? a : std::strtod(o.frames.c_str() + dash + 1, &end);
        if (!end || *end != '\0' || b < a) return "--frames expects A-B with A <= B, got '" + o.frames + "'";
        std::vector<double> frames;
        for (double f = a; f <= b; f += 1.0) frames.push_back(f);
        return frames;
    }
    if (o.frame) return std::vector<double>{*o.frame};
    return std::vector<double>{meta.startTimeCode.value_or(0.0)};
}

schema::CameraDepth cameraDepth(const UsdSceneHost& host, const std::string& cameraPath, double time) {
    schema::CameraDepth c = schema::defaultCameraDepth();
    ObscuraValue value{};
    const ObscuraSceneDelegate& sd = host.sceneDelegate();
    if (sd.getValue(sd.userData, cameraPath.c_str(), "clippingRange", time, &value) == OBSCURA_OK &&
        value.type == OBSCURA_VALUE_FLOAT2) {
        c.nearClip = static_cast<const float*>(value.data)[0];
        c.farClip = static_cast<const float*>(value.data)[1];
    }
    if (sd.getValue(sd.userData, cameraPath.c_str(), "projection", time, &value) == OBSCURA_OK &&
        value.type == OBSCURA_VALUE_TOKEN)
        c.orthographic = std::string(static_cast<const char* const*>(value.data)[0]) == "orthographic";
    return c;
}

// A progressive render (temporal AA accumulating a still, ObscuraRenderStats::converged) runs until
// it converges; the delegate converges after at most taa:frames + 2 renders (the maximum setting,
// the real-time frame a motion-blurred still starts with, and the frame that looks through the
// pixel centres), so this bound only guards against a plugin that never does.
constexpr int kMaxRendersPerFrame = 1026;

ObscuraStatus renderUntilConverged(Session& session, const ObscuraRenderPassDesc& desc) {
    ObscuraStatus status = OBSCURA_OK;
    for (int render = 0; render < kMaxRendersPerFrame; ++render) {
        status = session.api().render(session.delegate(), &desc);
        // The first render of a frame syncs what changed and, the first time, makes the pipelines.
        if (render == 0) session.phases().lap("first render");
        if (status != OBSCURA_OK && status != OBSCURA_ERROR_BAD_PRIM_DATA) return status;
        ObscuraRenderStats stats{};
        stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
        stats.structSize = sizeof(stats);
        if (session.api().getRenderStats(session.delegate(), &stats) != OBSCURA_OK || stats.converged) return status;
    }
    std::fprintf(stderr, "obscura: warning: the image did not converge in %d renders\n", kMaxRendersPerFrame);
    return status;
}

// The stage's render settings (UsdRender) under the flags, one set of options per render product:
// what a flag leaves unset comes from the RenderSettings prim --render-settings names, else the one
// the stage's renderSettingsPrimPath names, and from each of its products.
std::variant<std::vector<RenderOptions>, SessionError> withStageRenderSettings(const RenderOptions& o,
                                                                               const usda::Stage& stage) {
    const bool chosen = !o.renderSettings.empty();
    const std::string path = chosen ? o.renderSettings : stage.metadata().renderSettingsPrimPath;
    if (path.empty()) return std::vector<RenderOptions>{o};
    std::vector<HostMessage> messages;
    auto read = readStageRenderSettings(stage, path, messages);
    for (const HostMessage& m : messages) printHostMessage(m);
    if (auto* problem = std::get_if<std::string>(&read)) {
        if (chosen) return SessionError{kExitBadInput, "--render-settings: " + *problem};
        printHostMessage({false, "renderSettingsPrimPath: " + *problem + "; rendering without them", stage.metadata().where});
        return std::vector<RenderOptions>{o};
    }
    std::vector<StageRenderSettings> products = std::get<std::vector<StageRenderSettings>>(read);
    if (!o.output.empty() && products.size() > 1) {
        std::fprintf(stderr, "obscura: warning: -o names one file: %s's first product is written, %zu more are not\n",
                     path.c_str(), products.size() - 1);
        products.resize(1);
    }
    std::vector<RenderOptions> each;
    for (const StageRenderSettings& s : products) {
        RenderOptions p = o;
        if (p.camera.empty()) p.camera = s.camera;
        if (!p.width && s.resolution) p.width = (*s.resolution)[0];
        if (!p.height && s.resolution) p.height = (*s.resolution)[1];
        if (p.aovs.empty()) p.aovs = s.aovs;
        if (p.output.empty()) p.output = s.productName;
        // Ahead of the --set ones, which override them.
        std::vector<std::string> settings;
        if (s.pixelAspectRatio) {
            char text[64];
            std::snprintf(text, sizeof(text), "pixelAspectRatio=%.17g", *s.pixelAspectRatio);
            settings.emplace_back(text);
        }
        if (s.includedPurposes) settings.push_back("includedPurposes=" + *s.includedPurposes);
        if (s.disableMotionBlur) settings.push_back(*s.disableMotionBlur ? "motionBlur=off" : "motionBlur=on");
        if (s.disableDepthOfField) settings.push_back(*s.disableDepthOfField ? "dof=off" : "dof=on");
        settings.insert(settings.end(), o.settings.begin(), o.settings.end());
        p.settings = std::move(settings);
        each.push_back(std::move(p));
    }
    return each;
}

// One product: its frames rendered with `session` and written to its output.
int renderProduct(Session& session, const RenderOptions& o) {
    const int width = o.width.value_or(960), height = o.height.value_or(540);
    if (o.output.empty()) {
        std::fprintf(stderr, "obscura: no output: give -o, or render settings whose product has a productName\n");
        return kExitUsage;
    }
    bool exr = endsWith(o.output, ".exr"), png = endsWith(o.output, ".png");
    if (!exr && !png) {
        std::fprintf(stderr, "obscura: output must end in .exr or .png: %s\n", o.output.c_str());
        return kExitUsage;
    }
    if (width <= 0 || height <= 0) {
        std::fprintf(stderr, "obscura: --width and --height must be positive\n");
        return kExitUsage;
    }
    session.setVerbose(o.verbose);
    std::vector<std::string> settings = withMsaaSetting(o.settings, o.msaa);
    if (o.reference > 0) settings.push_back("reference=" + std::to_string(o.reference));
    if (auto problem = session.applySettings(settings)) {
        std::fprintf(stderr, "obscura: %s\n", problem->message.c_str());
        return problem->exitCode;
    }
    auto frames = frameList(o, session.stage().metadata());
    if (auto* problem = std::get_if<std::string>(&frames)) {
        std::fprintf(stderr, "obscura: %s\n", problem->c_str());
        return kExitUsage;
    }
    std::string camera = o.camera.empty() ? session.host().defaultCamera() : o.camera;
    if (camera.empty()) {
        camera = session.host().addFramingCamera(session.api(), session.delegate(), std::get<std::vector<double>>(frames).front());
        std::fprintf(stderr, "obscura: warning: %s has no camera; framing the scene's bounds from the front\n",
                     o.scene.c_str());
    }

    std::vector<std::string> aovs = png ? std::vector<std::string>{"display"}
                                        : (o.aovs.empty() ? std::vector<std::string>{"color"} : o.aovs);
    std::vector<std::string> buffers;
    std::vector<ObscuraAovBinding> bindings;
    for (const auto& aov : aovs) buffers.push_back(session.host().addRenderBuffer(session.api(), session.delegate(), aov, width, height));
    for (size_t i = 0; i < aovs.size(); ++i) bindings.push_back({aovs[i].c_str(), buffers[i].c_str()});

    int exitCode = kExitOk;
    const auto& frameTimes = std::get<std::vector<double>>(frames);
    bool timeVaryingDirty = false;
    for (size_t fi = 0; fi < frameTimes.size(); ++fi) {
        double frame = frameTimes[fi];
        std::string path = framePath(o.output, frame);
        if (o.skipExisting && std::filesystem::exists(path)) {
            std::fprintf(stderr, "obscura: frame %g (%zu/%zu): %s exists, skipped\n", frame, fi + 1, frameTimes.size(),
                         path.c_str());
            continue;
        }
        auto started = std::chrono::steady_clock::now();
        if (timeVaryingDirty) session.host().markTimeVarying(session.api(), session.delegate());
        timeVaryingDirty = true;
        ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(ObscuraRenderPassDesc),
                                   camera.c_str(), {0, 0, width, height}, frame,
                                   static_cast<uint32_t>(bindings.size()), bindings.data()};
        // Each frame of a sequence converges too: the first render of a frame syncs what changed
        // (the history is reprojected), the following ones accumulate the still.
        ObscuraStatus status = renderUntilConverged(session, desc);
        session.phases().lap("converged");
        if (status == OBSCURA_ERROR_BAD_PRIM_DATA) {
            exitCode = kExitBadInput;  // the frame still renders without the bad prims
        } else if (status != OBSCURA_OK) {
            std::fprintf(stderr, "obscura: render failed: %s\n", session.lastError().c_str());
            return status == OBSCURA_ERROR_NOT_FOUND || status == OBSCURA_ERROR_INVALID_ARGUMENT ? kExitBadInput
                                                                                                  : kExitPluginOrDevice;
        }
        std::vector<MappedAov> mapped;
        for (size_t i = 0; i < aovs.size(); ++i) {
            MappedAov m{aovs[i], {}};
            m.buffer.sType = OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER;
            m.buffer.structSize = sizeof(ObscuraMappedBuffer);
            if (session.api().mapRenderBuffer(session.delegate(), buffers[i].c_str(), &m.buffer) != OBSCURA_OK) {
                std::fprintf(stderr, "obscura: %s\n", session.lastError().c_str());
                return kExitPluginOrDevice;
            }
            mapped.push_back(m);
        }
        std::string problem = writeAtomically(path, [&](const std::string& file) {
            return png ? writePngDisplay(file, mapped[0].buffer)
                       : writeExrAovs(file, mapped, cameraDepth(session.host(), camera, frame));
        });
        for (const auto& b : buffers) session.api().unmapRenderBuffer(session.delegate(), b.c_str());
        session.phases().lap("written");
        if (session.verbose())
            std::fprintf(stderr, "obscura: info: frame %g: %s\n", frame, session.phases().report().c_str());
        if (!problem.empty()) {
            std::fprintf(stderr, "obscura: cannot write %s: %s\n", path.c_str(), problem.c_str());
            return kExitBadInput;
        }
        // A range (--frames) logs every frame: what a farm task's log needs to name.
        if (!o.frames.empty()) {
            double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
            std::fprintf(stderr, "obscura: frame %g (%zu/%zu) -> %s: %.0f ms on %s\n", frame, fi + 1, frameTimes.size(),
                         path.c_str(), ms, session.deviceName().c_str());
        }
    }
    return exitCode;
}

}  // namespace

int runRender(const RenderOptions& options) {
    auto opened = Session::open(options.scene, options.stage);
    if (auto* error = std::get_if<SessionError>(&opened)) {
        std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
        return error->exitCode;
    }
    std::unique_ptr<Session> session = std::move(std::get<std::unique_ptr<Session>>(opened));
    auto resolved = withStageRenderSettings(options, session->stage());
    if (auto* error = std::get_if<SessionError>(&resolved)) {
        std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
        return error->exitCode;
    }
    const std::vector<RenderOptions>& products = std::get<std::vector<RenderOptions>>(resolved);
    int exitCode = kExitOk;
    for (size_t i = 0; i < products.size(); ++i) {
        // Each product starts from the delegate's defaults: the settings one product authors
        // (pixel aspect, purposes, motion blur) do not carry over to the next.
        if (i > 0) {
            auto again = Session::open(options.scene, options.stage);
            if (auto* error = std::get_if<SessionError>(&again)) {
                std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
                return error->exitCode;
            }
            session = std::move(std::get<std::unique_ptr<Session>>(again));
        }
        const int code = renderProduct(*session, products[i]);
        if (code != kExitOk && code != kExitBadInput) return code;
        exitCode = std::max(exitCode, code);
    }
    return exitCode;
}

}  // namespace obscura::harness
