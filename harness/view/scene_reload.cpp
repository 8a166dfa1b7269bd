#include "harness/view/scene_reload.h"

#include <cstdio>

namespace obscura::harness::view {
namespace {

namespace fs = std::filesystem;

// The files a stage was read from (where its prims and attributes are authored), with their times.
std::map<std::string, fs::file_time_type> sceneFiles(const usda::Stage& stage) {
    std::map<std::string, fs::file_time_type> files;
    auto add = [&](const std::string& file) {
        std::error_code ec;
        // A layer inside a package is watched through the package.
        std::string path = file.substr(0, file.find('['));
        if (path.empty() || files.count(path)) return;
        auto time = fs::last_write_time(path, ec);
        if (!ec) files[path] = time;
    };
    for (const usda::Prim* prim : stage.prims()) {
        add(prim->where.file);
        for (const auto& [name, attribute] : prim->attributes) add(attribute.where.file);
    }
    return files;
}

}  // namespace

SceneReload::SceneReload(const Session& session)
    : files_(sceneFiles(session.stage())), lastLook_(std::chrono::steady_clock::now()) {}

bool SceneReload::filesChanged() {
    auto now = std::chrono::steady_clock::now();
    if (now - lastLook_ < std::chrono::milliseconds(500)) return false;
    lastLook_ = now;
    for (const auto& [path, time] : files_) {
        std::error_code ec;
        auto t = fs::last_write_time(path, ec);
        if (!ec && t != time) return true;
    }
    return false;
}

std::optional<size_t> SceneReload::reload(Session& session, ViewerScene& scene, const std::string& scenePath,
                                          const usda::StageOptions& options, double time) {
    auto opened = Session::openStage(scenePath, options);
    if (auto* error = std::get_if<SessionError>(&opened)) {
        std::fprintf(stderr, "obscura: %s (keeping the scene as it was)\n", error->message.c_str());
        files_ = sceneFiles(session.stage());  // looked at again after the next edit
        return std::nullopt;
    }
    auto stage = std::move(std::get<std::unique_ptr<usda::Stage>>(opened));
    auto host = std::make_unique<UsdSceneHost>(*stage);
    host->setMessageSink(printHostMessage);
    size_t touched = 0;
    if (host->adoptChanges(session.host(), session.api(), session.delegate(), time, touched) != OBSCURA_OK) {
        std::fprintf(stderr, "obscura: reload: %s\n", session.lastError().c_str());
        return std::nullopt;
    }
    scene.setHost(*host);
    session.replaceScene(std::move(stage), std::move(host));
    files_ = sceneFiles(session.stage());
    std::printf("reloaded %s: %zu prim%s changed\n", scenePath.c_str(), touched, touched == 1 ? "" : "s");
    std::fflush(stdout);
    return touched;
}

}  // namespace obscura::harness::view
