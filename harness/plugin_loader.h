// Plugin discovery as OpenUSD does it: plugInfo.json files on OBSCURA_PLUGINPATH (colon-separated
// folders or files) and in the default folder beside the harness (../lib/obscura/plugin/*/). A renderer
// plugin is a "library" entry whose Info.Types has a type with "HdRendererPlugin" among its
// bases; the harness dlopens its LibraryPath and negotiates the ABI through obscuraGetApi.
#pragma once

#include <obscura/obscura.h>

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace obscura::harness {

struct PluginInfo {
    std::filesystem::path plugInfoFile;
    std::string name;          // Plugins[].Name
    std::string typeName;      // the HdRendererPlugin type
    std::string displayName;
    int priority = 0;
    std::string abiVersion;    // "major.minor" declared in plugInfo.json
    std::filesystem::path library;
};

struct DiscoveryResult {
    std::vector<PluginInfo> plugins;     // highest priority first
    std::vector<std::string> problems;   // unreadable or malformed plugInfo.json files
};

// Searches `searchPath` (colon-separated; empty entries ignored) and then `defaultDir`.
DiscoveryResult discoverPlugins(const std::string& searchPath, const std::filesystem::path& defaultDir);

// A loaded plugin and its negotiated function table. Unloads on destruction.
class LoadedPlugin {
public:
    LoadedPlugin(LoadedPlugin&& other) noexcept;
    LoadedPlugin& operator=(LoadedPlugin&&) = delete;
    ~LoadedPlugin();
    const ObscuraApiV1& api() const { return *api_; }
    // The ABI 1.2 table (display interop), or null when the plugin's table is older.
    const ObscuraApiV1_2* interopApi() const {
        return api_->versionMinor >= 2 && api_->structSize >= sizeof(ObscuraApiV1_2)
                   ? reinterpret_cast<const ObscuraApiV1_2*>(api_)
                   : nullptr;
    }
    const PluginInfo& info() const { return info_; }

private:
    friend std::variant<LoadedPlugin, std::string> loadPlugin(const PluginInfo& info, uint32_t major, uint32_t minor);
    LoadedPlugin(PluginInfo info, void* handle, const ObscuraApiV1* api);
    PluginInfo info_;
    void* handle_ = nullptr;
    const ObscuraApiV1* api_ = nullptr;
};

// dlopen + obscuraGetApi(major, minor). The error string names the library and the reason.
std::variant<LoadedPlugin, std::string> loadPlugin(const PluginInfo& info, uint32_t major = OBSCURA_ABI_VERSION_MAJOR,
                                                   uint32_t minor = OBSCURA_ABI_VERSION_MINOR);

// The folder of the running executable.
std::filesystem::path executableDir();
// The plugin folder beside the running executable: <prefix>/lib/obscura/plugin for <prefix>/bin/obscura,
// in the build tree and in an installed prefix alike.
std::filesystem::path defaultPluginDir();

}  // namespace obscura::harness
