// A prim in the delegate's store (Hydra's rprim/sprim/bprim): its schema, dirty bits and the
// data its last successful sync produced. Sync pulls only what the dirty bits name.
#pragma once

#include "delegate/scene_access.h"

#include <obscura/obscura.h>

#include <string>

namespace obscura::gpu {
class Device;
}

namespace obscura::delegate {

class TextureCache;
class GeometryCache;

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
};

class Prim {
public:
    Prim(std::string path, const schema::PrimSchema& schema) : path_(std::move(path)), schema_(schema) {}
    virtual ~Prim() = default;

    const std::string& path() const { return path_; }
    const schema::PrimSchema& schema() const { return schema_; }
    ObscuraDirtyBits dirtyBits() const { return dirty_; }
    void markDirty(ObscuraDirtyBits bits) { dirty_ |= bits; }

    // Pulls what is dirty, rebuilds what that invalidates, clears the bits. On bad data the
    // prim is marked skipped (with the reason) and keeps no stale state; the bits are cleared
    // too, so the host must mark it dirty again after fixing the data.
    void sync(SyncContext& ctx);
    bool skipped() const { return !problem_.empty(); }
    const std::string& problem() const { return problem_; }

protected:
    virtual void pull(SceneAccess& scene, ObscuraDirtyBits bits, SyncContext& ctx) = 0;
    virtual void reset() {}

private:
    std::string path_;
    const schema::PrimSchema& schema_;
    ObscuraDirtyBits dirty_ = OBSCURA_DIRTY_ALL;
    std::string problem_;
};

}  // namespace obscura::delegate
