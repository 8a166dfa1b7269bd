// obscura view SCENE: opens the window and the session, runs the viewer (viewer.h) and checks that
// closing it released every Vulkan object.
#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/session.h"
#include "harness/view/viewer.h"

#include <cstdio>

namespace obscura::harness {

int runView(const ViewOptions& options) {
    auto window = view::ViewerWindow::open(options.width, options.height, "obscura view " + options.scene);
    if (auto* problem = std::get_if<std::string>(&window)) {
        std::fprintf(stderr, "obscura: %s\n", problem->c_str());
        return kExitPluginOrDevice;
    }
    int exitCode = kExitOk;
    {
        auto opened = Session::open(options.scene, options.stage);
        if (auto* error = std::get_if<SessionError>(&opened)) {
            std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
            return error->exitCode;
        }
        Session& session = *std::get<std::unique_ptr<Session>>(opened);
        if (auto problem = session.applySettings(options.settings)) {
            std::fprintf(stderr, "obscura: %s\n", problem->message.c_str());
            return problem->exitCode;
        }
        view::Viewer viewer(options, session, *std::get<std::unique_ptr<view::ViewerWindow>>(window));
        try {
            exitCode = viewer.run();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "obscura: viewer: %s\n", e.what());
            exitCode = kExitPluginOrDevice;
        }
        viewer.close();
        if (session.loggedErrors() > 0 && exitCode == kExitOk) exitCode = kExitPluginOrDevice;
    }
    // Closing released every Vulkan object: the validation layer reports any left at vkDestroyDevice.
    if (const uint32_t errors = view::DisplayDevice::validationErrors(); errors > 0) {
        std::fprintf(stderr, "obscura: %u Vulkan validation error(s) in the viewer\n", errors);
        if (exitCode == kExitOk) exitCode = kExitPluginOrDevice;
    }
    return exitCode;
}

}  // namespace obscura::harness
