#include "harness/frame_output.h"

#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <unistd.h>

namespace obscura::harness {
namespace fs = std::filesystem;

std::string framePath(const std::string& pattern, double frame) {
    auto first = pattern.find('#');
    if (first == std::string::npos) return pattern;
    auto last = pattern.find_first_not_of('#', first);
    size_t width = (last == std::string::npos ? pattern.size() : last) - first;
    char number[64];
    std::snprintf(number, sizeof(number), "%0*lld", int(width), static_cast<long long>(std::llround(frame)));
    return pattern.substr(0, first) + number + (last == std::string::npos ? "" : pattern.substr(last));
}

namespace {

// The temporary file being written, for the signal handler (which may only call async-signal-safe
// functions: unlink and _exit, on a path prepared beforehand).
char gPartialPath[4096];
std::atomic<bool> gPartialActive{false};

extern "C" void removePartialAndExit(int signal) {
    if (gPartialActive.load()) unlink(gPartialPath);
    _exit(128 + signal);
}

void installTerminationHandlers() {
    static bool installed = false;
    if (installed) return;
    installed = true;
    struct sigaction action {};
    action.sa_handler = removePartialAndExit;
    sigemptyset(&action.sa_mask);
    for (int s : {SIGTERM, SIGINT, SIGHUP}) {
        struct sigaction previous {};
        // A host that ignores a signal (nohup) keeps ignoring it.
        if (sigaction(s, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
        sigaction(s, &action, nullptr);
    }
}

}  // namespace

std::string writeAtomically(const std::string& path, const std::function<std::string(const std::string&)>& write) {
    fs::path target(path);
    // Hidden, named after the process, and keeping the extension (writers may look at it).
    fs::path partial = target.parent_path() /
                       ("." + target.stem().string() + ".partial-" + std::to_string(getpid()) + target.extension().string());
    std::string partialText = partial.string();
    if (partialText.size() >= sizeof(gPartialPath)) return "path too long";
    // A sequence's folder is made on demand, as renderers do for their output paths.
    std::error_code ec;
    if (!target.parent_path().empty()) fs::create_directories(target.parent_path(), ec);
    installTerminationHandlers();
    std::memcpy(gPartialPath, partialText.c_str(), partialText.size() + 1);
    gPartialActive.store(true);
    std::string problem = write(partialText);
    if (problem.empty() && std::rename(partialText.c_str(), path.c_str()) != 0)
        problem = std::string("cannot rename the finished image into place: ") + std::strerror(errno);
    if (!problem.empty()) unlink(partialText.c_str());
    gPartialActive.store(false);
    return problem;
}

}  // namespace obscura::harness
