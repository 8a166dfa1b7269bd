// The long soak: 10,000 frames (or argv[1]) of random edits through the ABI at 32x32
// (or argv[2] x argv[3]) with the in-memory test host; prints resident and Vulkan memory every
// 500 frames (and whenever the Vulkan memory changes) and the growth from frame 500 (after the
// warm-up) to the end. Figures go into bench/RESULTS.md.
#include "tests/support/random_edits.h"
#include "tests/support/resident_memory.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>

using namespace obscura::test;

int main(int argc, char** argv) {
    int frames = argc > 1 ? std::atoi(argv[1]) : 10000;
    int width = argc > 2 ? std::atoi(argv[2]) : 32, height = argc > 3 ? std::atoi(argv[3]) : 32;
    InMemoryHost host(false);
    RandomEditScene scene(host, 13, width, height);
    auto vulkanReserved = [&] { return vulkanMemoryReserved(host.api(), host.delegate()); };
    // Every kind of edit (each size, each settings combination) has been seen well before this.
    constexpr int kWarmup = 500;
    uint64_t residentAtWarmup = 0, vulkanAtWarmup = 0, vulkanBefore = 0;
    auto start = std::chrono::steady_clock::now();
    for (int frame = 1; frame <= frames; ++frame) {
        ObscuraStatus s = scene.editAndRender();
        if (s != OBSCURA_OK) {
            std::fprintf(stderr, "frame %d: status %d: %s\n", frame, int(s), host.lastError().c_str());
            return 1;
        }
        if (frame == kWarmup) residentAtWarmup = residentBytes(), vulkanAtWarmup = vulkanReserved();
        const uint64_t vulkan = vulkanReserved();
        const bool vulkanChanged = frame > 1 && vulkan != vulkanBefore;
        vulkanBefore = vulkan;
        if (frame % 500 == 0 || frame == frames || vulkanChanged)
            std::printf("frame %5d: resident %7.1f MiB, Vulkan memory %7.1f MiB, %.1f s\n", frame,
                        double(residentBytes()) / 1048576.0, double(vulkan) / 1048576.0,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (frames > kWarmup)
        std::printf("growth frames %d..%d: resident %+.2f%%, Vulkan memory %+.2f%%\n", kWarmup, frames,
                    100.0 * (double(residentBytes()) / double(residentAtWarmup) - 1.0),
                    100.0 * (double(vulkanReserved()) / double(vulkanAtWarmup) - 1.0));
    return 0;
}
