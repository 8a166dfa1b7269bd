#include "delegate/chained_stats.h"

#include <cstddef>

namespace obscura::delegate {
namespace {

// The 1.1 counters for any host; the 1.3 ones where its struct has room for them.
void fillMemoryStats(const gpu::MemoryAllocator& allocator, ObscuraMemoryStats& memory) {
    if (memory.structSize < offsetof(ObscuraMemoryStats, imageBytes)) return;
    memory.deviceMemoryReserved = allocator.bytesReserved();
    memory.deviceMemoryInUse = allocator.bytesInUse();
    memory.deviceMemoryBlocks = uint32_t(allocator.blockCount());
    if (memory.structSize < sizeof(ObscuraMemoryStats)) return;
    memory.imageBytes = allocator.bytesInUse(gpu::ResourceTiling::Optimal);
    memory.frameTargetBytes = allocator.bytesInUse(gpu::MemoryCategory::FrameTargets);
    memory.frameHistoryBytes = allocator.bytesInUse(gpu::MemoryCategory::FrameHistory);
    memory.textureBytes = allocator.bytesInUse(gpu::MemoryCategory::Textures);
    memory.geometryBytes = allocator.bytesInUse(gpu::MemoryCategory::Geometry);
    memory.renderBufferBytes = allocator.bytesInUse(gpu::MemoryCategory::RenderBuffers);
}

void fillCullingStats(const passes::CullingCounts& counts, ObscuraCullingStats& culling) {
    if (culling.structSize < sizeof(ObscuraCullingStats)) return;
    culling.draws = counts.draws;
    culling.drawsCulled = counts.drawsCulled;
    culling.instances = counts.instances;
    culling.instancesCulled = counts.instancesCulled;
    culling.triangles = counts.triangles;
    culling.trianglesCulled = counts.trianglesCulled;
    culling.milliseconds = counts.milliseconds;
    culling.drawsOutsideView = counts.drawsOutsideView;
    culling.instancesOutsideView = counts.instancesOutsideView;
    culling.trianglesOutsideView = counts.trianglesOutsideView;
}

// The chain's structs are the host's to write: the header is const only because input structs share it.
template <class T>
T& writable(const ObscuraStructHeader* header) {
    return *const_cast<T*>(reinterpret_cast<const T*>(header));
}

}  // namespace

void fillChainedStats(const void* first, const ChainedStatsSources& sources) {
    for (auto* next = static_cast<const ObscuraStructHeader*>(first); next;
         next = static_cast<const ObscuraStructHeader*>(next->pNext)) {
        if (next->sType == OBSCURA_STRUCTURE_TYPE_MEMORY_STATS)
            fillMemoryStats(sources.memory, writable<ObscuraMemoryStats>(next));
        if (next->sType == OBSCURA_STRUCTURE_TYPE_CULLING_STATS)
            fillCullingStats(sources.culling, writable<ObscuraCullingStats>(next));
        if (next->sType == OBSCURA_STRUCTURE_TYPE_INTEROP_STATS && next->structSize >= sizeof(ObscuraInteropStats))
            writable<ObscuraInteropStats>(next).semaphoreValue = sources.exportSemaphoreValue;
    }
}

}  // namespace obscura::delegate
