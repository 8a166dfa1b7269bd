// Scene reading, measured (Google Benchmark): a stage of 10,000 mesh prims (each a quad under its
// own translate, as USD text) composed, then opened and synced whole by the harness as `obscura
// render` does (the delegate's sync CPU time, ObscuraRenderStats::syncMilliseconds, as a counter);
// the same for references to crate geometry (the Open Chess Set's pieces, written by OpenUSD)
// under their own translates, instanceable or not, with the peak resident memory; the Open Chess
// Set (crate geometry, MaterialX looks) composed; and UsdSkel's linear blend skinning of 100,000
// points, 4 influences each among 64 joints, at one time (what the host does for each skinned prim
// at each time the delegate samples); and a glTF, an FBX and an OBJ file imported through Assimp in
// this process and in the harness's child process (what the isolation costs per import).
#include "harness/import/assimp_to_usda.h"
#include "harness/session.h"
#include "harness/usda/skinning.h"
#include "harness/usda/stage.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace obscura::bench {
namespace {

constexpr int kPrims = 10000;

std::string tenThousandPrims() {
    std::ostringstream text;
    text << "#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n"
         << "def Camera \"Camera\"\n{\n    double3 xformOp:translate = (50, 50, 150)\n"
         << "    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n"
         << "def DistantLight \"Sun\"\n{\n}\ndef Xform \"World\"\n{\n";
    for (int i = 0; i < kPrims; ++i)
        text << "    def Mesh \"M" << i << "\"\n    {\n"
             << "        point3f[] points = [(0, 0, 0), (0.8, 0, 0), (0.8, 0.8, 0), (0, 0.8, 0)]\n"
             << "        int[] faceVertexCounts = [4]\n        int[] faceVertexIndices = [0, 1, 2, 3]\n"
             << "        uniform token subdivisionScheme = \"none\"\n"
             << "        double3 xformOp:translate = (" << i % 100 << ", " << i / 100 << ", 0)\n"
             << "        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n    }\n";
    text << "}\n";
    return text.str();
}

void BM_ComposeTenThousandPrimsText(benchmark::State& state) {
    const std::string text = tenThousandPrims();
    for (auto _ : state) {
        auto stage = usda::Stage::openFromString(text, "ten_thousand.usda");
        benchmark::DoNotOptimize(stage);
    }
    state.counters["prims"] = kPrims;
}
BENCHMARK(BM_ComposeTenThousandPrimsText)->Unit(benchmark::kMillisecond);

// Open (compose and populate) and the first render's sync, as `obscura render` starts; the
// delegate's sync time as the counter sync_ms, and the prims the host inserted as inserted_prims.
// `settings`: render settings as `--set` takes them.
void openAndSync(benchmark::State& state, const std::filesystem::path& file,
                 const std::vector<std::string>& settings = {}) {
    double syncMs = 0;
    size_t inserted = 0;
    for (auto _ : state) {
        auto opened = harness::Session::open(file.string());
        if (!std::holds_alternative<std::unique_ptr<harness::Session>>(opened)) {
            state.SkipWithError(std::get<harness::SessionError>(opened).message.c_str());
            break;
        }
        harness::Session& session = *std::get<std::unique_ptr<harness::Session>>(opened);
        if (auto problem = session.applySettings(settings)) {
            state.SkipWithError(problem->message.c_str());
            break;
        }
        std::string buffer = session.host().addRenderBuffer(session.api(), session.delegate(), "color", 16, 16);
        ObscuraAovBinding binding{"color", buffer.c_str()};
        ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(desc), "/Camera",
                                   {0, 0, 16, 16}, 0.0, 1, &binding};
        session.api().render(session.delegate(), &desc);
        ObscuraRenderStats stats{};
        stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
        stats.structSize = sizeof(stats);
        session.api().getRenderStats(session.delegate(), &stats);
        syncMs = stats.syncMilliseconds;
        inserted = session.host().insertedPrims().size();
    }
    state.counters["sync_ms"] = syncMs;
    state.counters["inserted_prims"] = double(inserted);
}

void BM_OpenAndSyncTenThousandPrims(benchmark::State& state) {
    const auto file = std::filesystem::temp_directory_path() / "obscura_stage_benchmark.usda";
    std::ofstream(file) << tenThousandPrims();
    openAndSync(state, file);
    std::filesystem::remove(file);
}
BENCHMARK(BM_OpenAndSyncTenThousandPrims)->Unit(benchmark::kMillisecond)->Iterations(3);

const std::filesystem::path kChessAssets = std::filesystem::path(OBSCURA_CORPUS_DIR) / "full_assets/OpenChessSet/assets";
const char* kChessPieces[] = {"Pawn", "Rook", "Knight", "Bishop", "Queen", "King"};

// `count` references to the chess pieces' crate geometry (</Piece> of <Piece>_geom.usd, written by
// OpenUSD), round robin, each under its own translate on a grid 100 wide, `instanceable` or not: a
// text root layer over crate content. Written to a temporary folder, as nothing here writes crate
// files. The camera frames the whole grid, or with `closeUp` a few dozen pieces of its first rows
// from 1.2 units away (the rest outside the view, culled: the delegate still syncs every piece;
// the benchmark turns shadows off then).
std::filesystem::path crateReferences(int count, bool instanceable, bool closeUp = false) {
    const auto folder = std::filesystem::temp_directory_path() / "obscura_crate_references_benchmark";
    std::filesystem::create_directories(folder);
    std::ofstream text(folder / "root.usda");
    text << "#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n"
         << "def Camera \"Camera\"\n{\n    double3 xformOp:translate = " << (closeUp ? "(0.05, 0.05, 1.2)" : "(5, 1, 15)")
         << "\n"
         << "    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n"
         << "def DistantLight \"Sun\"\n{\n}\ndef Xform \"World\"\n{\n";
    for (int i = 0; i < count; ++i) {
        const char* piece = kChessPieces[size_t(i) % std::size(kChessPieces)];
        text << "    def Xform \"P" << i << "\" (\n        instanceable = " << (instanceable ? "true" : "false")
             << "\n        references = @"
             << (kChessAssets / piece / (std::string(piece) + "_geom.usd")).string() << "@</" << piece
             << ">\n    )\n    {\n"
             << "        double3 xformOp:translate = (" << 0.1 * (i % 100) << ", 0, " << 0.1 * (i / 100) << ")\n"
             << "        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n    }\n";
    }
    text << "}\n";
    return folder;
}

// The peak resident memory of the process so far, MiB.
double peakResidentMiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

void BM_ComposeCrateReferences(benchmark::State& state) {
    if (!std::filesystem::exists(kChessAssets)) {
        state.SkipWithError("no corpus");
        return;
    }
    const auto folder = crateReferences(int(state.range(0)), state.range(1) != 0);
    size_t prims = 0;
    for (auto _ : state) {
        auto stage = usda::Stage::open(folder / "root.usda");
        if (auto* error = std::get_if<usda::Error>(&stage)) {
            state.SkipWithError(error->str().c_str());
            break;
        }
        prims = std::get<std::unique_ptr<usda::Stage>>(stage)->prims().size();
    }
    state.counters["prims"] = double(prims);
    state.counters["peak_rss_mib"] = peakResidentMiB();
    std::filesystem::remove_all(folder);
}
// Arguments: references, instanceable. Run one at a time for each one's peak resident memory.
BENCHMARK(BM_ComposeCrateReferences)
    ->ArgNames({"references", "instanceable"})
    ->Args({250, 0})
    ->Args({500, 0})
    ->Args({kPrims, 0})
    ->Args({kPrims, 1})
    ->Unit(benchmark::kMillisecond);

void BM_OpenAndSyncCrateReferences(benchmark::State& state) {
    if (!std::filesystem::exists(kChessAssets)) {
        state.SkipWithError("no corpus");
        return;
    }
    const bool closeUp = state.range(2) != 0;
    const auto folder = crateReferences(int(state.range(0)), state.range(1) != 0, closeUp);
    // Close up, the sun's cascades would still reach the pieces between the view and the sun (all
    // rows behind the camera): shadows off, so the first frame draws what the view holds.
    openAndSync(state, folder / "root.usda", closeUp ? std::vector<std::string>{"shadows=0"} : std::vector<std::string>{});
    state.counters["peak_rss_mib"] = peakResidentMiB();
    std::filesystem::remove_all(folder);
}
BENCHMARK(BM_OpenAndSyncCrateReferences)
    ->ArgNames({"references", "instanceable", "close_up"})
    ->Args({25, 0, 0})
    ->Args({25, 1, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
// 10,000 references are synced instanced only: without instancing the plugin would triangulate and
// upload every piece (bench/RESULTS.md: about a second and 200 MB each on lavapipe). Once, seen
// close up: on lavapipe the first frame's drawing of all 10,000 pieces takes more than half an
// hour (`close_up:0` on a GPU).
BENCHMARK(BM_OpenAndSyncCrateReferences)
    ->ArgNames({"references", "instanceable", "close_up"})
    ->Args({kPrims, 1, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_ComposeOpenChessSet(benchmark::State& state) {
    const std::filesystem::path chess =
        std::filesystem::path(OBSCURA_CORPUS_DIR) / "full_assets/OpenChessSet/chess_set.usda";
    if (!std::filesystem::exists(chess)) {
        state.SkipWithError("no corpus");
        return;
    }
    for (auto _ : state) {
        auto stage = usda::Stage::open(chess);
        benchmark::DoNotOptimize(stage);
    }
}
BENCHMARK(BM_ComposeOpenChessSet)->Unit(benchmark::kMillisecond);

// A strip of 100,000 points along X bound to 64 joints in a chain, each point to the 4 nearest.
std::string skinnedStrip(int points, int joints) {
    std::ostringstream text;
    text << "#usda 1.0\ndef SkelRoot \"Rig\"\n{\n    def Skeleton \"Skel\"\n    {\n        uniform token[] joints = [";
    std::string path;
    for (int j = 0; j < joints; ++j) {
        path += (j ? "/j" : "j") + std::to_string(j);
        text << (j ? ", " : "") << '"' << path << '"';
    }
    text << "]\n        uniform matrix4d[] bindTransforms = [";
    for (int j = 0; j < joints; ++j)
        text << (j ? ", " : "") << "((1,0,0,0),(0,1,0,0),(0,0,1,0)," << "(" << j << ",0,0,1))";
    text << "]\n        uniform matrix4d[] restTransforms = [";
    for (int j = 0; j < joints; ++j) text << (j ? ", " : "") << "((1,0,0,0),(0,1,0,0),(0,0,1,0),(" << (j ? 1 : 0) << ",0,0,1))";
    text << "]\n        rel skel:animationSource = </Rig/Skel/Anim>\n"
         << "        def SkelAnimation \"Anim\"\n        {\n            uniform token[] joints = [";
    path.clear();
    for (int j = 0; j < joints; ++j) {
        path += (j ? "/j" : "j") + std::to_string(j);
        text << (j ? ", " : "") << '"' << path << '"';
    }
    text << "]\n            float3[] translations = [";
    for (int j = 0; j < joints; ++j) text << (j ? ", " : "") << "(" << (j ? 1 : 0) << ", 0, 0)";
    text << "]\n            quatf[] rotations = [";
    for (int j = 0; j < joints; ++j) text << (j ? ", " : "") << "(0.9961947, 0, 0, 0.0871557)";  // 10 degrees about Z
    text << "]\n        }\n    }\n    def Mesh \"Strip\"\n    {\n"
         << "        rel skel:skeleton = </Rig/Skel>\n        point3f[] points = [";
    for (int i = 0; i < points; ++i) text << (i ? ", " : "") << "(" << double(i) * joints / points << ", 0, 0)";
    text << "]\n        int[] primvars:skel:jointIndices = [";
    for (int i = 0; i < points; ++i) {
        const int first = std::min(joints - 4, std::max(0, i * joints / points - 1));
        for (int k = 0; k < 4; ++k) text << (i || k ? ", " : "") << first + k;
    }
    text << "] (\n            interpolation = \"vertex\"\n            elementSize = 4\n        )\n"
         << "        float[] primvars:skel:jointWeights = [";
    for (int i = 0; i < points; ++i) text << (i ? ", " : "") << "0.4, 0.3, 0.2, 0.1";
    text << "] (\n            interpolation = \"vertex\"\n            elementSize = 4\n        )\n    }\n}\n";
    return text.str();
}

void BM_SkinPoints(benchmark::State& state) {
    const int points = int(state.range(0));
    auto opened = usda::Stage::openFromString(skinnedStrip(points, 64), "skinned.usda");
    if (!std::holds_alternative<std::unique_ptr<usda::Stage>>(opened)) {
        state.SkipWithError(std::get<usda::Error>(opened).str().c_str());
        return;
    }
    const usda::Stage& stage = *std::get<std::unique_ptr<usda::Stage>>(opened);
    const usda::Prim& strip = *stage.find("/Rig/Strip");
    auto skinning = usda::resolveSkinning(stage, strip);
    if (!skinning || !std::holds_alternative<usda::Skinning>(*skinning)) {
        state.SkipWithError("the strip is not skinned");
        return;
    }
    const std::vector<double> rest = strip.attribute("points")->evaluate(0)->numbers;
    for (auto _ : state) {
        std::string problem;
        auto skinned = usda::skinPoints(stage, std::get<usda::Skinning>(*skinning), rest, 0.0, &problem);
        benchmark::DoNotOptimize(skinned);
    }
    state.SetItemsProcessed(state.iterations() * points);
}
BENCHMARK(BM_SkinPoints)->Arg(100000)->Unit(benchmark::kMillisecond);

// Argument 0: the import in this process; 1: in the child process, as the harness imports.
template <const char* kFile>
void BM_Import(benchmark::State& state) {
    const std::filesystem::path file = std::filesystem::path(OBSCURA_IMPORT_DATA_DIR) / kFile;
    for (auto _ : state) {
        auto imported = state.range(0) ? harness::importWithAssimp(file) : harness::importInThisProcess(file);
        if (auto* error = std::get_if<harness::ImportError>(&imported)) {
            state.SkipWithError(error->message.c_str());
            return;
        }
        benchmark::DoNotOptimize(imported);
    }
}
constexpr char kGltf[] = "scene.gltf", kFbx[] = "scene.fbx", kObj[] = "cube.obj";
BENCHMARK(BM_Import<kGltf>)->ArgName("child")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Import<kFbx>)->ArgName("child")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Import<kObj>)->ArgName("child")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace obscura::bench

BENCHMARK_MAIN();
