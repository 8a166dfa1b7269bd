// The harness's exit codes (DESIGN.md, CLI contract).
#pragma once

namespace obscura::harness {

enum ExitCode : int {
    kExitOk = 0,
    kExitBelowThreshold = 1,
    kExitUsage = 2,
    kExitBadInput = 3,
    kExitPluginOrDevice = 4,
};

}  // namespace obscura::harness
