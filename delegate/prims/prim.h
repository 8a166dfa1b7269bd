// A prim in the delegate's store (Hydra's rprim/sprim/bprim): its schema, dirty bits and the
// data its last successful sync produced. Sync pulls only what the dirty bits name.
#pragma once

#include "delegate/scene_access.h"

#include <obscura/obscura.h>

#include <functional>
#include <string>
#include <vector>

namespace obscura::gpu {
class Device;
}

namespace obscura::delegate {

class TextureCache;
class GeometryCache;
class BuiltMeshCache;

// A bit the delegate sets itself, never a host: the view (or the refineLevel setting) asks for
// another tessellation of what was pulled, without reading anything again.
constexpr ObscuraDirtyBits kDirtyTessellation = 0x80000000u;

// What a prim's sync does on the device (uploads, and the release of the GPU objects they replace),
// queued while it pulls and run on the calling thread afterwards: pulls may run on several threads
// at once, the device and the log are the calling thread's.
using DeviceWork = std::vector<std::function<void()>>;

struct SyncContext {
    const ObscuraSceneDelegate& sceneDelegate;
    gpu::Device& device;
    double time;
    double shutterOpen;   // absolute time codes of the camera's shutter
    double shutterClose;
    int refineLevel;      // render setting; meshes may override it
    double timeCodesPerSecond;  // render setting: velocities are per second, times in time codes
    TextureCache& textures;
    GeometryCache& geometry;
    BuiltMeshCache& builtMeshes;
    DeviceWork* deviceWork = nullptr;  // the prim being synced's queue

    void onDevice(std::function<void()> work) { deviceWork->push_back(std::move(work)); }
};

class Prim {
public:
    Prim(std::string path, const schema::PrimSchema& schema) : path_(std::move(path)), schema_(schema) {}
    virtual ~Prim() = default;

    const std::string& path() const { return path_; }
    const schema::PrimSchema& schema() const { return schema_; }
    ObscuraDirtyBits dirtyBits() const { return dirty_; }
    void markDirty(ObscuraDirtyBits bits) { dirty_ |= bits; }

    // Pulls what is dirty and rebuilds what that invalidates on the CPU, queuing what touches the
    // device on ctx.deviceWork. Prims may pull on different threads at once when the host's
    // callbacks are thread-safe. On bad data the prim is marked skipped (with the reason).
    void pullDirty(SyncContext& ctx);
    // On the calling thread, after pullDirty: runs the queued device work, or (skipped) drops
    // every stale state, then clears the bits; a skipped prim's host must mark it dirty again after
    // fixing the data. A prim whose sync failed half-way (an exception) keeps its bits.
    void commit(DeviceWork& work);
    // Both, on the calling thread.
    void sync(const SyncContext& ctx);
    bool skipped() const { return !problem_.empty(); }
    const std::string& problem() const { return problem_; }

protected:
    virtual void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) = 0;
    // Drops what the last sync produced; on the calling thread (it may release GPU objects).
    virtual void reset() {}

private:
    std::string path_;
    const schema::PrimSchema& schema_;
    ObscuraDirtyBits dirty_ = OBSCURA_DIRTY_ALL;
    std::string problem_;
};

}  // namespace obscura::delegate
