#include "delegate/prims/prim.h"

namespace obscura::delegate {

void Prim::sync(SyncContext& ctx) {
    // A skipped prim re-reads everything: its previous state was dropped.
    ObscuraDirtyBits bits = skipped() ? OBSCURA_DIRTY_ALL : dirty_;
    SceneAccess scene(ctx.sceneDelegate, schema_, path_, ctx.time);
    try {
        pull(scene, bits, ctx);
        problem_.clear();
    } catch (const PrimDataError& e) {
        problem_ = e.what();
        reset();
    }
    dirty_ = OBSCURA_DIRTY_CLEAN;
}

}  // namespace obscura::delegate
