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
    std::optional<double> frame;
    std::string frames;  // "A-B"
    int width = 960;
    int height = 540;
    std::vector<std::string> aovs;
    std::vector<std::string> settings;
    int reference = 0;  // sub-frames of the reference mode; 0: the normal frame
    std::optional<int> msaa;  // --msaa N: the render setting msaa
    bool verbose = false;     // print the plugin's info messages
    usda::CompositionLimits limits;  // --max-prims, --max-index-nodes, --max-stage-mib
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
    usda::CompositionLimits limits;
};

int runInfo();
int runRender(const RenderOptions& options);
int runCompare(const CompareOptions& options);
int runBench(const BenchOptions& options);

}  // namespace obscura::harness
