// Where a frame's image goes, and how it gets there: `####` in an output pattern becomes the frame
// number, and an image is written under a temporary name beside its final one and renamed into place
// when complete, so a killed render never leaves a half-written frame (a farm's re-run trusts every
// file it finds).
#pragma once

#include <functional>
#include <string>

namespace obscura::harness {

// "####" (the first run of #) becomes the frame number, zero-padded to the run's length.
std::string framePath(const std::string& pattern, double frame);

// Writes `path` through `write` (which returns "" or a problem) into a hidden temporary file in the same
// folder (made when missing), then renames it to `path`. On a problem, or when the process is terminated (SIGTERM, SIGINT,
// SIGHUP) meanwhile, the temporary file is removed. Returns "" or the problem.
std::string writeAtomically(const std::string& path, const std::function<std::string(const std::string&)>& write);

}  // namespace obscura::harness
