// What render and bench share: find and load the plugin, create a delegate that logs to
// stderr, open a scene and populate the delegate through the public ABI.
#pragma once

#include "harness/plugin_loader.h"
#include "harness/usd_scene_host.h"

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace obscura::harness {

// Wall-clock phases of a command (opening the scene, loading the plugin, rendering, writing), for
// -v: where a still's time goes.
class PhaseClock {
public:
    // Ends the current phase under `name` and starts the next.
    void lap(const char* name);
    // "name 12 ms, name 3 ms" in the order the phases ran; empties the list.
    std::string report();

private:
    std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
    std::string phases_;
};

struct SessionError {
    int exitCode;
    std::string message;
};

// "msaa=N" appended to `settings` when --msaa was given (a shortcut for --set msaa=N).
std::vector<std::string> withMsaaSetting(std::vector<std::string> settings, const std::optional<int>& msaa);

class Session {
public:
    // Loads the highest-priority plugin found (OBSCURA_PLUGINPATH, then beside the harness).
    static std::variant<std::unique_ptr<Session>, SessionError> open(const std::string& scenePath,
                                                                     const usda::StageOptions& options = {});
    ~Session();

    const ObscuraApiV1& api() const { return plugin_->api(); }
    const ObscuraApiV1_2* interopApi() const { return plugin_->interopApi(); }
    ObscuraDelegate delegate() const { return delegate_; }
    UsdSceneHost& host() { return *host_; }
    const usda::Stage& stage() const { return *stage_; }
    std::string lastError() const { return api().lastError(delegate_); }
    uint32_t loggedErrors() const { return loggedErrors_; }
    // The delegate's render stats, with the display interop stats chained when `interop` is given.
    ObscuraRenderStats renderStats(ObscuraInteropStats* interop = nullptr) const;
    // The GPU time of each pass of the last render.
    std::vector<ObscuraPassTiming> passTimings() const;
    // The Vulkan device the delegate renders with (from its render stats; empty before the first render).
    std::string deviceName() const;
    // Also print the plugin's info messages (device, loaded textures, the MSAA tagged share).
    void setVerbose(bool verbose) { verbose_ = verbose; }
    bool verbose() const { return verbose_; }
    // The phases of `open` (stage: reading the scene, while the plugin is loaded and its delegate
    // made; delegate: the wait for that beyond the stage; populate), then whatever the command
    // laps on it.
    PhaseClock& phases() { return phases_; }

    // Reads a scene file as `open` does (USD layers, or glTF/FBX/OBJ through Assimp).
    static std::variant<std::unique_ptr<usda::Stage>, SessionError> openStage(const std::string& scenePath,
                                                                              const usda::StageOptions& options);
    // The scene read again (the viewer's reload): the delegate pulls from `host` from now on; the
    // previous stage and host are destroyed.
    void replaceScene(std::unique_ptr<usda::Stage> stage, std::unique_ptr<UsdSceneHost> host);

    // Applies "key=value" settings; returns the first problem.
    std::optional<SessionError> applySettings(const std::vector<std::string>& settings);

private:
    Session() = default;
    static void logToStderr(void* user, ObscuraLogLevel level, const char* message);
    // Loads the plugin (loadBestPlugin) and creates its delegate, logging to stderr.
    std::optional<SessionError> createDelegate();

    std::optional<LoadedPlugin> plugin_;
    std::unique_ptr<usda::Stage> stage_;
    std::unique_ptr<UsdSceneHost> host_;
    ObscuraDelegate delegate_ = nullptr;
    uint32_t loggedErrors_ = 0;
    bool verbose_ = false;
    PhaseClock phases_;
};

// Prints a host message to stderr as "obscura: file:line:column: warning: text".
void printHostMessage(const HostMessage& message);

// Loads the best plugin without a scene (for `obscura info`).
std::variant<LoadedPlugin, SessionError> loadBestPlugin();

}  // namespace obscura::harness
