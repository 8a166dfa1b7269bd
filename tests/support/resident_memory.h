// The resident set size of this process (Linux /proc/self/statm), for tests and benchmarks that
// watch memory over many frames.
#pragma once

#include <cstdint>
#include <cstdio>
#include <unistd.h>

namespace obscura::test {

inline uint64_t residentBytes() {
    unsigned long sizePages = 0, residentPages = 0;
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    if (std::fscanf(f, "%lu %lu", &sizePages, &residentPages) != 2) residentPages = 0;
    std::fclose(f);
    return uint64_t(residentPages) * uint64_t(sysconf(_SC_PAGESIZE));
}

}  // namespace obscura::test
