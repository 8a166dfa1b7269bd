// obscura: the standalone host. Loads the renderer plugin through its C ABI and renders,
// compares and benchmarks scenes (DESIGN.md, CLI contract). CLI11 lives in this file only.
#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/plugin_variant_fallbacks.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace {

// How the scene is loaded (usda::StageOptions): what composing it may build, and variant
// fallbacks. Render, bench and view share them.
void addStageOptions(CLI::App& command, obscura::usda::StageOptions& options) {
    obscura::usda::CompositionLimits& limits = options.limits;
    command.add_option("--max-prims", limits.maxPrims, "stop composing beyond this many prims")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command.add_option("--max-index-nodes", limits.maxIndexNodes, "composition arcs one prim may gather")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command
        .add_option_function<size_t>(
            "--max-stage-mib", [&limits](size_t mib) { limits.maxMemoryBytes = mib << 20; },
            "memory the composed stage may hold, MiB (default " + std::to_string(limits.maxMemoryBytes >> 20) + ")")
        ->check(CLI::Range(size_t(1), size_t(1) << 40));
    command
        .add_option_function<std::vector<std::string>>(
            "--variant-fallback",
            [&options](const std::vector<std::string>& entries) {
                for (const std::string& entry : entries) {
                    const size_t equals = entry.find('=');
                    std::vector<std::string>& variants = options.variantFallbacks[entry.substr(0, equals)];
                    variants.clear();  // given again: the later list replaces the earlier
                    for (size_t start = equals + 1; start <= entry.size();) {
                        const size_t comma = std::min(entry.find(',', start), entry.size());
                        variants.push_back(entry.substr(start, comma - start));
                        start = comma + 1;
                    }
                }
            },
            "SET=A[,B...]: a variant set without an authored selection takes the first of these variants it has "
            "(repeatable)")
        ->check(CLI::Validator(
            [](const std::string& entry) -> std::string {
                const size_t equals = entry.find('=');
                if (equals == 0 || equals == std::string::npos || equals + 1 == entry.size() ||
                    entry.find(",,") != std::string::npos || entry.back() == ',' || entry[equals + 1] == ',')
                    return "'" + entry + "' is not SET=VARIANT[,VARIANT...]";
                return {};
            },
            "SET=A[,B...]"));
}

// The variant fallbacks of the plugins on PXR_PLUGINPATH_NAME, as UsdStage reads them, under the
// sets --variant-fallback gives.
void addPluginVariantFallbacks(obscura::usda::StageOptions& options) {
    const char* searchPath = std::getenv("PXR_PLUGINPATH_NAME");
    const obscura::harness::PluginVariantFallbacks plugins =
        obscura::harness::readPluginVariantFallbacks(searchPath ? searchPath : "");
    for (const auto& w : plugins.warnings)
        std::fprintf(stderr, "obscura: warning: %s:%d:%d: %s\n", w.where.file.c_str(), w.where.line, w.where.column,
                     w.message.c_str());
    for (const auto& [set, variants] : plugins.fallbacks) options.variantFallbacks.emplace(set, variants);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace obscura::harness;
    CLI::App app{"obscura: render USD scenes with the Obscura render delegate plugin"};
    app.require_subcommand(1);

    app.add_subcommand("info", "plugins found, ABI versions, Vulkan devices, render settings");

    GradeChartOptions gradeChart;
    auto* gc = app.add_subcommand("grade-chart", "write the neutral colour-grading chart (render setting grading:chart)");
    gc->add_option("--write", gradeChart.output, "the chart's .png")->required();
    gc->add_option("--into", gradeChart.into, "a screenshot to put the chart over (its top-left corner)");

    RenderOptions render;
    double frame = 0;
    auto* r = app.add_subcommand("render", "render a scene to an image");
    r->add_option("scene", render.scene, "scene file (.usda, .usdc, .usd, .usdz, .gltf, .glb, .fbx, .obj)")->required();
    r->add_option("-o,--output", render.output,
                  "output .exr (all AOVs, linear) or .png (display); #### = frame (default: the render product's "
                  "productName)");
    r->add_option("--camera", render.camera, "camera prim path (default: the render settings', else the first camera)");
    r->add_option("--render-settings", render.renderSettings,
                  "RenderSettings prim whose camera, resolution, pixel aspect, purposes and product's AOVs are used "
                  "(default: the stage's renderSettingsPrimPath); flags override them");
    auto* frameOpt = r->add_option("--frame", frame, "time code to render");
    r->add_option("--frames", render.frames, "range A-B of frames");
    r->add_option("--width", render.width, "image width in pixels (default: the render settings', else 960)")
        ->check(CLI::PositiveNumber);
    r->add_option("--height", render.height, "image height in pixels (default: the render settings', else 540)")
        ->check(CLI::PositiveNumber);
    r->add_option("--aov", render.aovs, "AOVs for .exr: color,depth,normal,albedo,motion,primId,instanceId")->delimiter(',');
    r->add_option("--set", render.settings, "render setting key=value (repeatable)");
    r->add_option("--reference", render.reference,
                  "ground truth: average N sub-frames sampling the lens aperture, shutter and pixel "
                  "(render setting `reference`)")
        ->check(CLI::NonNegativeNumber);
    r->add_option("--msaa", render.msaa, "G-buffer samples per pixel (render setting `msaa`)");
    r->add_flag("-v,--verbose", render.verbose, "print the plugin's info messages");
    r->add_flag("--skip-existing", render.skipExisting, "do not render frames whose output file exists (resume a range)");
    frameOpt->excludes(r->get_option("--frames"));
    addStageOptions(*r, render.stage);

    CompareOptions compare;
    auto* c = app.add_subcommand("compare", "compare two images; exit 1 below a threshold");
    c->add_option("a", compare.a, "first image")->required();
    c->add_option("b", compare.b, "second image")->required();
    c->add_option("--psnr-min", compare.psnrMin, "fail below this PSNR (dB)");
    c->add_option("--ssim-min", compare.ssimMin, "fail below this SSIM");
    c->add_option("--diff", compare.diff, "write a difference image (PNG)");

    BenchOptions bench;
    auto* b = app.add_subcommand("bench", "per-pass GPU timestamp medians");
    b->add_option("scene", bench.scene, "scene file (.usda, .usdc, .usd, .usdz, .gltf, .glb, .fbx, .obj)")->required();
    b->add_option("--frames", bench.frames, "measured frames")->check(CLI::PositiveNumber);
    b->add_option("--width", bench.width, "image width")->check(CLI::PositiveNumber);
    b->add_option("--height", bench.height, "image height")->check(CLI::PositiveNumber);
    b->add_flag("--json", bench.json, "machine-readable output");
    b->add_flag("--changing-camera", bench.changingCamera,
                "mark the camera changed every frame: temporal AA measured as under camera motion");
    b->add_option("--set", bench.settings, "render setting key=value (repeatable)");
    b->add_option("--msaa", bench.msaa, "G-buffer samples per pixel (render setting `msaa`)");
    b->add_flag("-v,--verbose", bench.verbose, "print the plugin's info messages");
    b->add_option("--display", bench.display,
                  "also show each frame on a Vulkan device of the harness and time it: readback (through host memory) "
                  "or shared (exported device memory, ABI 1.2)")
        ->check(CLI::IsMember({"readback", "shared"}));
    addStageOptions(*b, bench.stage);

    ViewOptions viewOptions;
    auto* v = app.add_subcommand("view", "an interactive window: orbit, pick, HUD, progressive refinement");
    v->add_option("scene", viewOptions.scene, "scene file (.usda, .usdc, .usd, .usdz, .gltf, .glb, .fbx, .obj)")->required();
    v->add_option("--camera", viewOptions.camera, "scene camera to start with (default: the first one)");
    v->add_option("--width", viewOptions.width, "window width")->check(CLI::PositiveNumber);
    v->add_option("--height", viewOptions.height, "window height")->check(CLI::PositiveNumber);
    v->add_option("--script", viewOptions.script, "play input events from a file (also OBSCURA_VIEW_SCRIPT)")
        ->envname("OBSCURA_VIEW_SCRIPT");
    v->add_option("--display", viewOptions.display,
                  "how frames reach the window: shared (exported device memory), readback (through host memory), "
                  "auto (shared where the devices can)")
        ->check(CLI::IsMember({"auto", "shared", "readback"}));
    v->add_option("--set", viewOptions.settings, "render setting key=value (repeatable)");
    addStageOptions(*v, viewOptions.stage);

    FarmSubmitOptions farmSubmit;
    FarmJobOptions farmJob;
    auto* farm = app.add_subcommand("farm", "frame ranges as array jobs on a Slurm cluster (docs/FARM.md)");
    farm->require_subcommand(1);
    auto* fs = farm->add_subcommand("submit", "submit a frame range; prints the job id");
    fs->add_option("scene", farmSubmit.scene, "scene file")->required();
    fs->add_option("-o,--output", farmSubmit.output, "output pattern with #### (.exr or .png)")->required();
    fs->add_option("--frames", farmSubmit.frames, "range A-B of frames")->required();
    fs->add_option("--chunk", farmSubmit.chunk, "frames per task")->check(CLI::PositiveNumber);
    fs->add_option("--partition", farmSubmit.partition, "scheduler partition (default: the cluster's)");
    fs->add_option("--render-args", farmSubmit.renderArgs, "more `obscura render` arguments (repeatable)")
        ->allow_extra_args(false);
    fs->add_option("--max-retries", farmSubmit.maxRetries, "restarts of a task before it gives up")
        ->check(CLI::NonNegativeNumber);
    fs->add_flag("--force", farmSubmit.force, "render frames whose file exists too");
    auto* fst = farm->add_subcommand("status", "frames done, running, pending and failed; exit 0 when complete");
    fst->add_option("job", farmJob.job, "job id or job folder")->required();
    auto* fr = farm->add_subcommand("resubmit", "submit again the tasks whose frames are missing");
    fr->add_option("job", farmJob.job, "job id or job folder")->required();

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? kExitOk : kExitUsage;
    }
    if (*frameOpt) render.frame = frame;
    if (app.got_subcommand("info")) return runInfo();
    if (gc->parsed()) return runGradeChart(gradeChart);
    if (app.got_subcommand("render")) {
        addPluginVariantFallbacks(render.stage);
        return runRender(render);
    }
    if (app.got_subcommand("compare")) return runCompare(compare);
    if (fs->parsed()) return runFarmSubmit(farmSubmit);
    if (fst->parsed()) return runFarmStatus(farmJob);
    if (fr->parsed()) return runFarmResubmit(farmJob);
    if (v->parsed()) {
        addPluginVariantFallbacks(viewOptions.stage);
        const char* validation = std::getenv("OBSCURA_VALIDATION");
        viewOptions.validation = validation && *validation && std::string(validation) != "0";
        return runView(viewOptions);
    }
    addPluginVariantFallbacks(bench.stage);
    return runBench(bench);
}
