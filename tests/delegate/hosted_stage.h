// A composed USD stage rendered through the harness's scene host (harness/usd_scene_host.h) and
// the plugin, as `obscura render` does: for tests of what the host computes from a stage (texture
// networks, purpose, inherited visibility, displayColor) and what the plugin draws from it.
#pragma once

#include "harness/plugin_loader.h"
#include "harness/usd_scene_host.h"
#include "tests/support/expected_errors.h"

#include <obscura/obscura.h>

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace obscura::test {

// USDA text of the delegate tests' camera (render_fixture.h's lit-plane camera): at (0, 0, 5)
// looking down -Z, a 50 mm lens behind a square 20.955 mm aperture, so its view spans
// [-1.04775, 1.04775]^2 at z = 0; clipping range (0.1, 100). `attributes` (whole lines, e.g. a
// shutter) are added to its body.
std::string usdaCamera(const std::string& attributes = "");

struct HostedStage {
    std::unique_ptr<usda::Stage> stage;
    std::optional<harness::LoadedPlugin> plugin;
    ObscuraDelegate delegate = nullptr;
    std::unique_ptr<harness::UsdSceneHost> host;  // in place: its callback table points at it
    std::vector<std::string> errors;  // logged by the plugin: checked against expectError when the stage goes away
    std::vector<std::string> warnings;  // logged by the plugin
    ObscuraStatus lastStatus = OBSCURA_OK;  // of the last render

    explicit HostedStage(std::variant<std::unique_ptr<usda::Stage>, usda::Error> opened);
    ~HostedStage();
    HostedStage(const HostedStage&) = delete;
    HostedStage& operator=(const HostedStage&) = delete;

    const ObscuraApiV1& api() const { return plugin->api(); }
    // Renders one AOV at `time` through the stage's first camera (kWidth x kHeight) and returns
    // its values, `channels` per pixel; int32 AOVs (primId) come back converted to float.
    std::vector<float> renderAov(const std::string& aov, size_t channels, double time = 0.0);
    std::vector<float> renderAlbedo() { return renderAov("albedo", 3); }
    // The stage read again after an edit, adopted as the viewer adopts a file changed on disk
    // (UsdSceneHost::adoptChanges at `time`); returns how many prims the host touched.
    size_t adopt(std::variant<std::unique_ptr<usda::Stage>, usda::Error> edited, double time = 0.0);
    // A render setting that is one token.
    void setToken(const std::string& name, const std::string& token);
    void setBool(const std::string& name, bool on);
    // Whether the host reported a message containing `fragment`, and how many such it reported.
    bool warned(const std::string& fragment) const { return messagesWith(fragment) > 0; }
    size_t messagesWith(const std::string& fragment) const;
    // What the host serves the plugin for `attribute` of the prim at `path` at time 0: numbers
    // (float-typed values), one token; a missing value fails the test. `served`: whether it
    // serves one at all.
    std::vector<float> floats(const std::string& path, const std::string& attribute) const;
    std::string token(const std::string& path, const std::string& attribute) const;
    bool served(const std::string& path, const std::string& attribute) const;
    // A logged error containing `fragment` is one this test provokes; any other fails it.
    void expectError(std::string fragment) { expected_.add(std::move(fragment)); }

private:
    ExpectedErrors expected_;
    static void log(void* user, ObscuraLogLevel level, const char* message);
};

}  // namespace obscura::test
