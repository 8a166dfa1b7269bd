// Incremental sync, measured (Google Benchmark): a scene of 10,000 mesh prims and 1,000,000
// triangles; the initial sync, then re-syncs after changing one transform, one material, and
// after adding and removing one prim. Reported times are the delegate's own CPU time for sync
// (ObscuraRenderStats::syncMilliseconds) and, separately, for packing the frame's records. Each
// runs with a host whose callbacks run on the render thread only (argument 0) and with one that
// declares them thread-safe (OBSCURA_SCENE_DELEGATE_THREAD_SAFE, argument 1): sync then pulls the
// dirty rprims in parallel.
#include "tests/support/in_memory_host.h"

#include <benchmark/benchmark.h>

#include <memory>

namespace obscura::test {
namespace {

constexpr int kPrims = 10000;
constexpr int kQuadsPerSide = 7;

// A 7x7 grid of quads (98 triangles) plus one more quad: 100 triangles per prim.
std::map<std::string, HostValue> gridMesh(const std::string& material) {
    std::vector<std::array<float, 3>> points;
    for (int y = 0; y <= kQuadsPerSide; ++y)
        for (int x = 0; x <= kQuadsPerSide; ++x) points.push_back({float(x) * 0.1f, float(y) * 0.1f, 0.0f});
    std::vector<int32_t> counts, indices;
    auto quad = [&](int a, int b, int c, int d) {
        counts.push_back(4);
        indices.insert(indices.end(), {a, b, c, d});
    };
    const int row = kQuadsPerSide + 1;
    for (int y = 0; y < kQuadsPerSide; ++y)
        for (int x = 0; x < kQuadsPerSide; ++x) quad(y * row + x, y * row + x + 1, (y + 1) * row + x + 1, (y + 1) * row + x);
    quad(0, 1, row + 1, row);
    return {{"points", HostValue::points(points)},
            {"faceVertexCounts", HostValue::intArray(counts)},
            {"faceVertexIndices", HostValue::intArray(indices)},
            {"subdivisionScheme", HostValue::token("none")},
            {"material:binding", HostValue::path(material)}};
}

struct BigScene {
    std::unique_ptr<InMemoryHost> host;
    explicit BigScene(const benchmark::State& state)
        : host(std::make_unique<InMemoryHost>(false, state.range(0) != 0)) {
        host->addCamera("/Camera", translation(0, 0, 200));
        for (int m = 0; m < 10; ++m) host->addPrim("material", "/Looks/M" + std::to_string(m), {});
        host->addPrim("distantLight", "/Sun", {});
        host->addRenderBuffer("/Buffers/color", "float32Vec4", 16, 16);
        for (int i = 0; i < kPrims; ++i)
            host->addPrim("mesh", "/Meshes/M" + std::to_string(i), gridMesh("/Looks/M" + std::to_string(i % 10)),
                          translation(i % 100 - 50, i / 100 - 50, 0));
    }
    ObscuraRenderStats render() {
        if (host->render("/Camera", {{"color", "/Buffers/color"}}) != OBSCURA_OK) throw std::runtime_error(host->lastError());
        ObscuraRenderStats s{};
        s.structSize = sizeof(s);
        host->api().getRenderStats(host->delegate(), &s);
        return s;
    }
};

void report(benchmark::State& state, const ObscuraRenderStats& s) {
    state.SetIterationTime(s.syncMilliseconds / 1000.0);
    state.counters["sync_ms"] = s.syncMilliseconds;
    state.counters["frame_setup_ms"] = s.frameSetupMilliseconds;
    state.counters["prims_synced"] = s.primsSynced;
    state.counters["triangles"] = double(s.trianglesDrawn);
}

void InitialSync(benchmark::State& state) {
    for (auto _ : state) {
        state.PauseTiming();
        BigScene scene(state);
        state.ResumeTiming();
        report(state, scene.render());
    }
}

void ResyncOneTransform(benchmark::State& state) {
    BigScene scene(state);
    scene.render();
    int i = 0;
    for (auto _ : state) {
        scene.host->setTransform("/Meshes/M7", translation(i++ % 7, 0, 0));
        scene.host->api().markDirty(scene.host->delegate(), "/Meshes/M7", OBSCURA_DIRTY_TRANSFORM);
        report(state, scene.render());
    }
}

void ResyncOneMaterial(benchmark::State& state) {
    BigScene scene(state);
    scene.render();
    int i = 0;
    for (auto _ : state) {
        scene.host->set("/Looks/M3", "inputs:roughness", HostValue::floatValue(float(i++ % 10) / 10.0f));
        scene.host->api().markDirty(scene.host->delegate(), "/Looks/M3", OBSCURA_DIRTY_PARAMS);
        report(state, scene.render());
    }
}

void AddAndRemoveOnePrim(benchmark::State& state) {
    BigScene scene(state);
    scene.render();
    int i = 0;
    for (auto _ : state) {
        std::string path = "/Extra/E" + std::to_string(i++);
        scene.host->addPrim("mesh", path, gridMesh("/Looks/M0"));
        report(state, scene.render());
        scene.host->api().removePrim(scene.host->delegate(), path.c_str());
        scene.render();
    }
}

// Manual time (the delegate's own sync time), with either host.
void withBothHosts(benchmark::internal::Benchmark* b) {
    b->UseManualTime()->Unit(benchmark::kMillisecond)->ArgName("threadSafeHost")->Arg(0)->Arg(1);
}

BENCHMARK(InitialSync)->Apply(withBothHosts)->Iterations(3);
BENCHMARK(ResyncOneTransform)->Apply(withBothHosts)->Iterations(20);
BENCHMARK(ResyncOneMaterial)->Apply(withBothHosts)->Iterations(20);
BENCHMARK(AddAndRemoveOnePrim)->Apply(withBothHosts)->Iterations(20);

}  // namespace
}  // namespace obscura::test

BENCHMARK_MAIN();
