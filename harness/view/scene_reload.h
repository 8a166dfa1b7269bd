// Reading the scene again when one of its files changes on disk. The files the stage was read from
// are watched by their modification times; the scene read again is compared with the one the
// delegate holds, and only the prims an edit changed are inserted, removed or marked dirty
// (UsdSceneHost::adoptChanges), as an edited layer re-syncs only what it changed in usdview.
#pragma once

#include "harness/session.h"
#include "harness/view/viewer_scene.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace obscura::harness::view {

class SceneReload {
public:
    // Watches the files `session`'s stage was read from.
    explicit SceneReload(const Session& session);

    // Whether one of the files changed since the stage was read (looked at every half second).
    bool filesChanged();
    // Reads `scenePath` again into `session`, `scene` answering from the new host; returns how many
    // prims changed, or nothing where the scene stays as it was (a file caught half-written, an
    // edit with a mistake: the problem is printed).
    std::optional<size_t> reload(Session& session, ViewerScene& scene, const std::string& scenePath,
                                 const usda::StageOptions& options, double time);

private:
    std::map<std::string, std::filesystem::file_time_type> files_;
    std::chrono::steady_clock::time_point lastLook_;
};

}  // namespace obscura::harness::view
