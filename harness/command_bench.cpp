#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/session.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace obscura::harness {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int runBench(const BenchOptions& o) {
    if (o.frames <= 0 || o.width <= 0 || o.height <= 0) {
        std::fprintf(stderr, "obscura: --frames, --width and --height must be positive\n");
        return kExitUsage;
    }
    auto opened = Session::open(o.scene, o.limits);
    if (auto* error = std::get_if<SessionError>(&opened)) {
        std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
        return error->exitCode;
    }
    Session& session = *std::get<std::unique_ptr<Session>>(opened);
    session.setVerbose(o.verbose);
    if (auto problem = session.applySettings(withMsaaSetting(o.settings, o.msaa))) {
        std::fprintf(stderr, "obscura: %s\n", problem->message.c_str());
        return problem->exitCode;
    }
    std::string camera = session.host().defaultCamera();
    if (camera.empty()) {
        std::fprintf(stderr, "obscura: %s has no camera\n", o.scene.c_str());
        return kExitBadInput;
    }
    std::string buffer = session.host().addRenderBuffer(session.api(), session.delegate(), "color", o.width, o.height);
    ObscuraAovBinding binding{"color", buffer.c_str()};
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
        ObscuraStatus s = session.api().render(session.delegate(), &desc);
        if (s != OBSCURA_OK && s != OBSCURA_ERROR_BAD_PRIM_DATA) {
            std::fprintf(stderr, "obscura: render failed: %s\n", session.lastError().c_str());
            return kExitPluginOrDevice;
        }
        uint32_t count = 0;
        session.api().getPassTimings(session.delegate(), nullptr, &count);
        std::vector<ObscuraPassTiming> timings(count);
        for (auto& t : timings) t.structSize = sizeof(ObscuraPassTiming);
        session.api().getPassTimings(session.delegate(), timings.data(), &count);
        if (i < kWarmup) {
            for (uint32_t k = 0; k < count; ++k) {
                if (!warmupOnly.count(timings[k].pass)) warmupOrder.push_back(timings[k].pass);
                warmupOnly[timings[k].pass] = timings[k].milliseconds;
            }
            continue;
        }
        double total = 0;
        for (uint32_t k = 0; k < count; ++k) {
            if (!samples.count(timings[k].pass)) order.push_back(timings[k].pass);
            samples[timings[k].pass].push_back(timings[k].milliseconds);
            total += timings[k].milliseconds;
        }
        samples["total"].push_back(total);
    }
    order.push_back("total");
    std::erase_if(warmupOrder, [&](const std::string& pass) { return samples.count(pass) > 0; });
    // The delegate's Vulkan memory after the measured frames: what a steady frame holds.
    ObscuraMemoryStats memory{OBSCURA_STRUCTURE_TYPE_MEMORY_STATS, nullptr, sizeof(memory), 0, 0, 0};
    ObscuraRenderStats stats{};
    stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
    stats.pNext = &memory;
    stats.structSize = sizeof(stats);
    session.api().getRenderStats(session.delegate(), &stats);
    constexpr double kMiB = 1024.0 * 1024.0;

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
        std::printf("}, \"device_memory_mib\": {\"in_use\": %.1f, \"reserved\": %.1f}}\n",
                    double(memory.deviceMemoryInUse) / kMiB, double(memory.deviceMemoryReserved) / kMiB);
    } else {
        std::printf("%s on %s, %dx%d, %d frames, %llu triangles (GPU timestamp medians)\n", o.scene.c_str(),
                    stats.deviceName, o.width, o.height, o.frames, static_cast<unsigned long long>(stats.trianglesDrawn));
        for (const auto& name : order) std::printf("  %-16s %10.4f ms\n", name.c_str(), median(samples[name]));
        if (!warmupOrder.empty()) std::printf("once (in warm-up, when their inputs changed; last run):\n");
        for (const auto& name : warmupOrder) std::printf("  %-16s %10.4f ms\n", name.c_str(), warmupOnly[name]);
        std::printf("device memory: %.1f MiB in use, %.1f MiB reserved\n", double(memory.deviceMemoryInUse) / kMiB,
                    double(memory.deviceMemoryReserved) / kMiB);
    }
    return kExitOk;
}

}  // namespace obscura::harness
