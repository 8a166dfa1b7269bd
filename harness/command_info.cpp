#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/plugin_loader.h"
#include "harness/session.h"

#include <cstdio>
#include <cstdlib>

namespace obscura::harness {

int runInfo() {
    std::printf("obscura harness, ABI %d.%d\n", OBSCURA_ABI_VERSION_MAJOR, OBSCURA_ABI_VERSION_MINOR);
    const char* env = std::getenv("OBSCURA_PLUGINPATH");
    DiscoveryResult found = discoverPlugins(env ? env : "", defaultPluginDir());
    std::printf("plugins:\n");
    for (const auto& p : found.plugins)
        std::printf("  %s (%s) priority %d, ABI %s\n    %s\n    %s\n", p.displayName.c_str(), p.typeName.c_str(),
                    p.priority, p.abiVersion.c_str(), p.plugInfoFile.c_str(), p.library.c_str());
    for (const auto& problem : found.problems) std::printf("  problem: %s\n", problem.c_str());
    auto plugin = loadBestPlugin();
    if (auto* error = std::get_if<SessionError>(&plugin)) {
        std::fprintf(stderr, "obscura: %s\n", error->message.c_str());
        return error->exitCode;
    }
    const ObscuraApiV1& api = std::get<LoadedPlugin>(plugin).api();
    std::printf("loaded: %s, ABI %u.%u\n", std::get<LoadedPlugin>(plugin).info().displayName.c_str(), api.versionMajor,
                api.versionMinor);

    uint32_t count = 0;
    if (api.enumerateDevices(nullptr, &count) != OBSCURA_OK) {
        std::fprintf(stderr, "obscura: %s\n", api.lastError(nullptr));
        return kExitPluginOrDevice;
    }
    std::vector<ObscuraDeviceInfo> devices(count);
    api.enumerateDevices(devices.data(), &count);
    std::printf("Vulkan devices:\n");
    for (uint32_t i = 0; i < count; ++i) {
        const auto& d = devices[i];
        std::printf("  [%u] %s (%s%s) Vulkan %u.%u, MSAA up to %ux, driver %s\n", i, d.name,
                    d.isDiscrete ? "discrete GPU" : d.isCpu ? "CPU" : "GPU", "", d.apiVersion >> 22,
                    (d.apiVersion >> 12) & 0x3ffu, d.maxMsaaSamples, d.driver);
    }
    std::printf("render settings:\n");
    const char* name = nullptr;
    const char* description = nullptr;
    for (uint32_t i = 0; api.describeRenderSetting(i, &name, &description) == OBSCURA_OK; ++i)
        std::printf("  %-14s %s\n", name, description);
    return kExitOk;
}

}  // namespace obscura::harness
