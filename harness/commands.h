// The harness's subcommands (DESIGN.md, CLI contract). main.cpp parses the command line.
#pragma once

#include "harness/usda/stage.h"

#include <optional>
#include <string>
#include <vector>

namespace obscura::harness {

struct RenderOptions {
    std::string scene;
    std::string output;
    std::string camera;
    std::string renderSettings;  // --render-settings: a RenderSettings prim; "": the stage's renderSettingsPrimPath
    std::optional<double> frame;
    std::string frames;  // "A-B"
    // Unset: the render settings' resolution, else 960 x 540.
    std::optional<int> width;
    std::optional<int> height;
    std::vector<std::string> aovs;
    std::vector<std::string> settings;
    int reference = 0;  // sub-frames of the reference mode; 0: the normal frame
    std::optional<int> msaa;  // --msaa N: the render setting msaa
    bool verbose = false;     // print the plugin's info messages
    bool skipExisting = false;  // frames whose output file exists are not rendered again (resumable ranges)
    usda::StageOptions stage;  // --max-prims, --max-index-nodes, --max-stage-mib, --variant-fallback
};

struct CompareOptions {
    std::string a;
    std::string b;
    std::optional<double> psnrMin;
    std::optional<double> ssimMin;
    std::string diff;
};

struct BenchOptions {
    std::string scene;
    int frames = 50;
    int width = 1920;
    int height = 1080;
    bool json = false;
    // Mark the camera changed before every frame (it does not move): temporal passes then work as
    // under camera motion (temporal AA reprojects and clamps) instead of settling into a still.
    bool changingCamera = false;
    std::vector<std::string> settings;
    std::optional<int> msaa;  // --msaa N: the render setting msaa
    bool verbose = false;     // print the plugin's info messages (e.g. the MSAA tagged share per frame)
    // Also show each frame on a device of the harness's own, as the viewer does, and time it:
    // "readback" (map, copy to host memory) or "shared" (the exported memory, ABI 1.2); "" not.
    std::string display;
    usda::StageOptions stage;
};

// obscura view SCENE: the interactive viewer (README "The viewer").
struct ViewOptions {
    std::string scene;
    std::string camera;                  // a scene camera to start with (default: the first, else the free camera)
    int width = 960;
    int height = 540;
    std::string script;                  // input events to play (harness/view/input_script.h)
    std::string display = "auto";        // shared (exported memory), readback (mapped) or auto (shared where possible)
    std::vector<std::string> settings;
    bool validation = false;             // OBSCURA_VALIDATION: the viewer's Vulkan validated too
    usda::StageOptions stage;
};

// obscura farm submit: a frame range as an array job of the scheduler (docs/FARM.md).
struct FarmSubmitOptions {
    std::string scene;
    std::string output;                  // with #### for the frame number
    std::string frames;                  // "A-B", integers
    long long chunk = 1;                 // frames per task
    std::string partition;
    std::vector<std::string> renderArgs; // more `obscura render` arguments, split at whitespace
    int maxRetries = 2;
    bool force = false;                  // render frames that exist already
};

// obscura farm status|resubmit JOB: the id `farm submit` printed, or the job folder.
struct FarmJobOptions {
    std::string job;
};

// obscura grade-chart --write CHART.png [--into SCREENSHOT]: the neutral grading chart, alone or
// over the top-left corner of a screenshot.
struct GradeChartOptions {
    std::string output;
    std::string into;
};

int runInfo();
int runGradeChart(const GradeChartOptions& options);
int runRender(const RenderOptions& options);
int runCompare(const CompareOptions& options);
int runBench(const BenchOptions& options);
int runView(const ViewOptions& options);
int runFarmSubmit(const FarmSubmitOptions& options);
int runFarmStatus(const FarmJobOptions& options);
int runFarmResubmit(const FarmJobOptions& options);

}  // namespace obscura::harness
