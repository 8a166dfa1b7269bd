#include "delegate/prims/prim.h"

namespace obscura::delegate {

void Prim::pullDirty(SyncContext& ctx) {
    // A skipped prim re-reads everything: its previous state was dropped.
    ObscuraDirtyBits bits = skipped() ? OBSCURA_DIRTY_ALL : dirty_;
    SceneAccess scene(ctx.sceneDelegate, schema_, path_, ctx.time, bits);
    try {
        pull(scene, bits, ctx);
        problem_.clear();
    } catch (const PrimDataError& e) {
        problem_ = e.what();
    }
}

void Prim::commit(DeviceWork& work) {
    if (skipped()) {
        reset();
    } else {
        for (auto& run : work) run();
    }
    dirty_ = OBSCURA_DIRTY_CLEAN;
}

void Prim::sync(const SyncContext& ctx) {
    DeviceWork work;
    SyncContext own = ctx;
    own.deviceWork = &work;
    pullDirty(own);
    commit(work);
}

}  // namespace obscura::delegate
