#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/session.h"
#include "harness/view/render_buffer_display.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

namespace obscura::harness {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Each frame shown on a Vulkan device of the harness's own, as `obscura view` shows it: through host
// memory (map, copy into a buffer of that device) or through the plugin's exported memory.
class DisplayTiming {
public:
    // After the first render; returns the problem, or "".
    std::string start(Session& session, const std::string& buffer, const std::string& mode) {
        view::DisplayDeviceOptions options;
        options.deviceName = session.deviceName();
        std::optional<ObscuraExternalBuffer> exported;
        if (mode == "shared") {
            auto made = view::exportRenderBuffer(session, buffer);
            if (auto* problem = std::get_if<std::string>(&made)) return *problem;
            exported = std::get<ObscuraExternalBuffer>(made);
            options.deviceUUID = exported->deviceUUID;
        }
        auto created = view::DisplayDevice::create(options);
        if (auto* problem = std::get_if<std::string>(&created)) return *problem;
        device_ = std::move(std::get<std::unique_ptr<view::DisplayDevice>>(created));
        image_ = std::make_unique<view::AovImage>(*device_);
        if (exported) {
            auto imported = view::DisplaySource::import(*device_, *exported);
            if (auto* problem = std::get_if<std::string>(&imported)) return *problem;
            source_ = std::move(std::get<std::unique_ptr<view::DisplaySource>>(imported));
        }
        return {};
    }
    // After a render: the frame into the display image; returns the wall time it took, ms.
    double show(Session& session, const std::string& buffer) {
        auto start = std::chrono::steady_clock::now();
        if (!source_ || !source_->shared()) view::copyRenderBuffer(session, *device_, buffer, source_);
        view::showSource(session, *device_, *source_, *image_, view::AovView::Display);
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    ~DisplayTiming() {
        source_.reset();
        image_.reset();
    }

private:
    std::unique_ptr<view::DisplayDevice> device_;
    std::unique_ptr<view::DisplaySource> source_;
    std::unique_ptr<view::AovImage> image_;
};

}  // namespace

int runBench(const BenchOptions& o) {
    if (o.frames <= 0 || o.width <= 0 || o.height <= 0) {
        std::fprintf(stderr, "obscura: --frames, --width and --height must be positive\n");
        return kExitUsage;
    }
    auto opened = Session::open(o.scene, o.stage);
    if (auto* error = std::get_if<SessionError>(&opened)) {
        std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
        return error->exitCode;
    }
    Session& session = *std::get<std::unique_ptr<Session>>(opened);
    session.setVerbose(o.verbose);
    // Whole frames: a still that converged within the run would otherwise keep its colour and leave
    // out the lighting (taa:reuseConverged); a --set of its own comes after and wins.
    std::vector<std::string> settings{"taa:reuseConverged=off"};
    settings.insert(settings.end(), o.settings.begin(), o.settings.end());
    if (auto problem = session.applySettings(withMsaaSetting(settings, o.msaa))) {
        std::fprintf(stderr, "obscura: %s\n", problem->message.c_str());
        return problem->exitCode;
    }
    std::string camera = session.host().defaultCamera();
    if (camera.empty()) {
        std::fprintf(stderr, "obscura: %s has no camera\n", o.scene.c_str());
        return kExitBadInput;
    }
    // The viewer shows the display AOV; without --display the bench reads colour, as before.
    const char* aov = o.display.empty() ? "color" : "display";
    std::string buffer = session.host().addRenderBuffer(session.api(), session.delegate(), aov, o.width, o.height);
    ObscuraAovBinding binding{aov, buffer.c_str()};
    DisplayTiming display;
    std::vector<double> renderCalls, shows;
    double time = session.stage().metadata().startTimeCode.value_or(0.0);
    ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(ObscuraRenderPassDesc),
                               camera.c_str(), {0, 0, o.width, o.height}, time, 1, &binding};

    // Warm-up frames compile pipelines (and JIT shaders on lavapipe); they are not measured, except
    // for passes that run only then: work done once per change of its inputs (the environment
    // prefilter of a textured dome), reported apart with the time of its last run.
    constexpr int kWarmup = 3;
    std::map<std::string, std::vector<double>> samples;
    std::vector<std::string> order;
    std::map<std::string, double> warmupOnly;
    std::vector<std::string> warmupOrder;
    for (int i = 0; i < kWarmup + o.frames; ++i) {
        if (o.changingCamera) session.api().markDirty(session.delegate(), camera.c_str(), OBSCURA_DIRTY_TRANSFORM);
        auto renderStart = std::chrono::steady_clock::now();
        ObscuraStatus s = session.api().render(session.delegate(), &desc);
        const double renderCall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - renderStart).count();
        if (s != OBSCURA_OK && s != OBSCURA_ERROR_BAD_PRIM_DATA) {
            std::fprintf(stderr, "obscura: render failed: %s\n", session.lastError().c_str());
            return kExitPluginOrDevice;
        }
        if (!o.display.empty()) {
            if (i == 0)
                if (std::string problem = display.start(session, buffer, o.display); !problem.empty()) {
                    std::fprintf(stderr, "obscura: --display %s: %s\n", o.display.c_str(), problem.c_str());
                    return kExitPluginOrDevice;
                }
            const double shown = display.show(session, buffer);
            if (i >= kWarmup) renderCalls.push_back(renderCall), shows.push_back(shown);
        }
        const std::vector<ObscuraPassTiming> timings = session.passTimings();
        const size_t count = timings.size();
        if (i < kWarmup) {
            for (size_t k = 0; k < count; ++k) {
                if (!warmupOnly.count(timings[k].pass)) warmupOrder.push_back(timings[k].pass);
                warmupOnly[timings[k].pass] = timings[k].milliseconds;
            }
            continue;
        }
        double total = 0;
        for (size_t k = 0; k < count; ++k) {
            if (!samples.count(timings[k].pass)) order.push_back(timings[k].pass);
            samples[timings[k].pass].push_back(timings[k].milliseconds);
            total += timings[k].milliseconds;
        }
        samples["total"].push_back(total);
    }
    order.push_back("total");
    std::erase_if(warmupOrder, [&](const std::string& pass) { return samples.count(pass) > 0; });
    // The delegate's Vulkan memory after the measured frames: what a steady frame holds.
    ObscuraCullingStats culling{};
    culling.sType = OBSCURA_STRUCTURE_TYPE_CULLING_STATS;
    culling.structSize = sizeof(culling);
    ObscuraMemoryStats memory{};
    memory.sType = OBSCURA_STRUCTURE_TYPE_MEMORY_STATS;
    memory.pNext = &culling;
    memory.structSize = sizeof(memory);
    ObscuraRenderStats stats{};
    stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
    stats.pNext = &memory;
    stats.structSize = sizeof(stats);
    session.api().getRenderStats(session.delegate(), &stats);
    constexpr double kMiB = 1024.0 * 1024.0;
    // What the memory in use holds, by kind: images and buffers, then the owners that hold most.
    const uint64_t named = memory.frameTargetBytes + memory.frameHistoryBytes + memory.textureBytes +
                           memory.geometryBytes + memory.renderBufferBytes;
    const std::pair<const char*, uint64_t> kinds[] = {
        {"images", memory.imageBytes},
        {"buffers", memory.deviceMemoryInUse - memory.imageBytes},
        {"frame_targets", memory.frameTargetBytes},
        {"frame_history", memory.frameHistoryBytes},
        {"textures", memory.textureBytes},
        {"geometry", memory.geometryBytes},
        {"render_buffers", memory.renderBufferBytes},
        {"other", memory.deviceMemoryInUse - named},
    };

    if (o.json) {
        std::printf("{\"scene\": \"%s\", \"device\": \"%s\", \"width\": %d, \"height\": %d, \"frames\": %d, "
                    "\"triangles\": %llu, \"passes\": {",
                    o.scene.c_str(), stats.deviceName, o.width, o.height, o.frames,
                    static_cast<unsigned long long>(stats.trianglesDrawn));
        for (size_t i = 0; i < order.size(); ++i)
            std::printf("%s\"%s\": {\"median_ms\": %.4f}", i ? ", " : "", order[i].c_str(), median(samples[order[i]]));
        std::printf("}, \"once\": {");
        for (size_t i = 0; i < warmupOrder.size(); ++i)
            std::printf("%s\"%s\": {\"last_ms\": %.4f}", i ? ", " : "", warmupOrder[i].c_str(),
                        warmupOnly[warmupOrder[i]]);
        std::printf("}");
        if (!o.display.empty())
            std::printf(", \"display\": {\"mode\": \"%s\", \"render_call_ms\": %.4f, \"show_ms\": %.4f}", o.display.c_str(),
                        median(renderCalls), median(shows));
        std::printf(", \"culling\": {\"draws\": %u, \"draws_culled\": %u, \"instances\": %llu, "
                    "\"instances_culled\": %llu, \"triangles\": %llu, \"triangles_culled\": %llu, \"cpu_ms\": %.4f, "
                    "\"draws_outside_view\": %u, \"instances_outside_view\": %llu, \"triangles_outside_view\": %llu}",
                    culling.draws, culling.drawsCulled, static_cast<unsigned long long>(culling.instances),
                    static_cast<unsigned long long>(culling.instancesCulled),
                    static_cast<unsigned long long>(culling.triangles),
                    static_cast<unsigned long long>(culling.trianglesCulled), culling.milliseconds,
                    culling.drawsOutsideView, static_cast<unsigned long long>(culling.instancesOutsideView),
                    static_cast<unsigned long long>(culling.trianglesOutsideView));
        std::printf(", \"device_memory_mib\": {\"in_use\": %.1f, \"reserved\": %.1f",
                    double(memory.deviceMemoryInUse) / kMiB, double(memory.deviceMemoryReserved) / kMiB);
        for (const auto& [kind, bytes] : kinds) std::printf(", \"%s\": %.1f", kind, double(bytes) / kMiB);
        std::printf("}}\n");
    } else {
        std::printf("%s on %s, %dx%d, %d frames, %llu triangles (GPU timestamp medians)\n", o.scene.c_str(),
                    stats.deviceName, o.width, o.height, o.frames, static_cast<unsigned long long>(stats.trianglesDrawn));
        for (const auto& name : order) std::printf("  %-16s %10.4f ms\n", name.c_str(), median(samples[name]));
        if (!warmupOrder.empty()) std::printf("once (in warm-up, when their inputs changed; last run):\n");
        for (const auto& name : warmupOrder) std::printf("  %-16s %10.4f ms\n", name.c_str(), warmupOnly[name]);
        std::printf("device memory: %.1f MiB in use, %.1f MiB reserved\n", double(memory.deviceMemoryInUse) / kMiB,
                    double(memory.deviceMemoryReserved) / kMiB);
        for (const auto& [kind, bytes] : kinds) std::printf("  %-16s %10.1f MiB\n", kind, double(bytes) / kMiB);
        // The last frame's camera view (render setting occlusionCulling).
        std::printf("occlusion culling (last frame): %u of %u draws, %llu of %llu instances, %llu of %llu triangles "
                    "culled; %.3f ms CPU\n",
                    culling.drawsCulled, culling.draws, static_cast<unsigned long long>(culling.instancesCulled),
                    static_cast<unsigned long long>(culling.instances),
                    static_cast<unsigned long long>(culling.trianglesCulled),
                    static_cast<unsigned long long>(culling.triangles), culling.milliseconds);
        std::printf("outside the view (last frame): %u draws, %llu instances, %llu triangles\n", culling.drawsOutsideView,
                    static_cast<unsigned long long>(culling.instancesOutsideView),
                    static_cast<unsigned long long>(culling.trianglesOutsideView));
        if (!o.display.empty())
            std::printf("display (%s, wall-clock medians): render call %.4f ms, showing the frame %.4f ms\n",
                        o.display.c_str(), median(renderCalls), median(shows));
    }
    return kExitOk;
}

}  // namespace obscura::harness
