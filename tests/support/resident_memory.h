// The resident set size of this process (Linux /proc/self/statm) and a delegate's Vulkan memory,
// for tests and benchmarks that watch memory over many frames.
#pragma once

#include "obscura/obscura.h"

#include <cstdint>
#include <cstdio>
#include <unistd.h>

namespace obscura::test {

// Whether the resident set measures what the plugin holds. Under AddressSanitizer freed memory waits
// in a quarantine (256 MB by default) before it is reused, so a soak's resident size grows with
// nothing held; there LeakSanitizer checks what is held, and the normal build asserts the bar.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kResidentSizeIsThePlugins = false;
#else
inline constexpr bool kResidentSizeIsThePlugins = true;
#endif

inline uint64_t residentBytes() {
    unsigned long sizePages = 0, residentPages = 0;
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    if (std::fscanf(f, "%lu %lu", &sizePages, &residentPages) != 2) residentPages = 0;
    std::fclose(f);
    return uint64_t(residentPages) * uint64_t(sysconf(_SC_PAGESIZE));
}

// Bytes of VkDeviceMemory the delegate holds (ObscuraMemoryStats); 0 when the call fails.
inline uint64_t vulkanMemoryReserved(const ObscuraApiV1& api, ObscuraDelegate delegate) {
    ObscuraMemoryStats memory{OBSCURA_STRUCTURE_TYPE_MEMORY_STATS, nullptr, sizeof(memory), 0, 0, 0};
    ObscuraRenderStats stats{};
    stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
    stats.pNext = &memory;
    stats.structSize = sizeof(stats);
    return api.getRenderStats(delegate, &stats) == OBSCURA_OK ? memory.deviceMemoryReserved : 0;
}

}  // namespace obscura::test
