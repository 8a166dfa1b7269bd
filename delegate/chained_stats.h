// The output structs a host chains to ObscuraRenderStats::pNext, filled from the delegate's state:
// each only where its structSize says the host's struct has room, every sType, pNext and structSize
// left as the host set them.
#pragma once

#include "gpu/memory.h"
#include "passes/frame_scene.h"

#include <obscura/obscura.h>

#include <cstdint>

namespace obscura::delegate {

struct ChainedStatsSources {
    const gpu::MemoryAllocator& memory;
    const passes::CullingCounts& culling;
    uint64_t exportSemaphoreValue;  // 0 before any export
};

// Fills every struct of the chain starting at `first` (the render stats' pNext) that it knows.
void fillChainedStats(const void* first, const ChainedStatsSources& sources);

}  // namespace obscura::delegate
