#include "harness/plugin_loader.h"

#include "harness/plug_info_json.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace obscura::harness {
namespace fs = std::filesystem;

namespace {

void readPlugInfo(const fs::path& file, DiscoveryResult& out) {
    std::ifstream in(file);
    if (!in) {
        out.problems.push_back(file.string() + ": cannot be read");
        return;
    }
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    nlohmann::json doc;
    try {
        doc = parsePlugInfoJson(text);
    } catch (const nlohmann::json::parse_error& e) {
        const auto [line, column] = plugInfoLineAndColumn(text, e.byte);
        out.problems.push_back(file.string() + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                               e.what());
        return;
    }
    if (!doc.is_object() || !doc.contains("Plugins") || !doc["Plugins"].is_array()) {
        out.problems.push_back(file.string() + ": no \"Plugins\" array");
        return;
    }
    for (const auto& p : doc["Plugins"]) {
        if (!p.is_object() || p.value("Type", "") != "library") continue;
        fs::path root = file.parent_path() / p.value("Root", ".");
        std::string library = p.value("LibraryPath", "");
        if (library.empty()) {
            out.problems.push_back(file.string() + ": plugin without LibraryPath");
            continue;
        }
        const auto* types = p.contains("Info") && p["Info"].contains("Types") ? &p["Info"]["Types"] : nullptr;
        if (!types || !types->is_object()) continue;
        for (const auto& [typeName, type] : types->items()) {
            if (!type.is_object() || !type.contains("bases") || !type["bases"].is_array()) continue;
            bool renderer = std::any_of(type["bases"].begin(), type["bases"].end(),
                                        [](const auto& b) { return b.is_string() && b == "HdRendererPlugin"; });
            if (!renderer) continue;
            PluginInfo info;
            info.plugInfoFile = file;
            info.name = p.value("Name", typeName);
            info.typeName = typeName;
            info.displayName = type.value("displayName", typeName);
            info.priority = type.value("priority", 0);
            info.abiVersion = type.value("abiVersion", "");
            info.library = fs::path(library).is_absolute() ? fs::path(library) : root / library;
            out.plugins.push_back(std::move(info));
        }
    }
}

void searchFolder(const fs::path& entry, DiscoveryResult& out, std::set<fs::path>& seen) {
    std::error_code ec;
    auto consider = [&](const fs::path& f) {
        fs::path canonical = fs::weakly_canonical(f, ec);
        if (seen.insert(canonical).second) readPlugInfo(f, out);
    };
    if (fs::is_regular_file(entry, ec)) {
        consider(entry);
        return;
    }
    if (!fs::is_directory(entry, ec)) return;
    if (fs::exists(entry / "plugInfo.json", ec)) consider(entry / "plugInfo.json");
    // One level down, as USD's "*/" pattern: <dir>/<plugin>/plugInfo.json.
    for (const auto& child : fs::directory_iterator(entry, ec))
        if (child.is_directory(ec) && fs::exists(child.path() / "plugInfo.json", ec)) consider(child.path() / "plugInfo.json");
}

}  // namespace

DiscoveryResult discoverPlugins(const std::string& searchPath, const fs::path& defaultDir) {
    DiscoveryResult out;
    std::set<fs::path> seen;
    std::stringstream ss(searchPath);
    std::string entry;
    while (std::getline(ss, entry, ':'))
        if (!entry.empty()) searchFolder(entry, out, seen);
    if (!defaultDir.empty()) searchFolder(defaultDir, out, seen);
    // Highest priority first; discovery order breaks ties (search path before default).
    std::stable_sort(out.plugins.begin(), out.plugins.end(),
                     [](const PluginInfo& a, const PluginInfo& b) { return a.priority > b.priority; });
    return out;
}

LoadedPlugin::LoadedPlugin(PluginInfo info, void* handle, const ObscuraApiV1* api)
    : info_(std::move(info)), handle_(handle), api_(api) {}

LoadedPlugin::LoadedPlugin(LoadedPlugin&& o) noexcept : info_(std::move(o.info_)), handle_(o.handle_), api_(o.api_) {
    o.handle_ = nullptr;
    o.api_ = nullptr;
}

LoadedPlugin::~LoadedPlugin() {
    if (handle_) dlclose(handle_);
}

std::variant<LoadedPlugin, std::string> loadPlugin(const PluginInfo& info, uint32_t major, uint32_t minor) {
    void* handle = dlopen(info.library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) return info.library.string() + ": " + dlerror();
    auto getApi = reinterpret_cast<PFN_obscuraGetApi>(dlsym(handle, OBSCURA_GET_API_SYMBOL));
    if (!getApi) {
        dlclose(handle);
        return info.library.string() + ": no " OBSCURA_GET_API_SYMBOL " symbol (not an Obscura plugin)";
    }
    const void* table = nullptr;
    ObscuraStatus s = getApi(major, minor, &table);
    if (s != OBSCURA_OK || !table) {
        dlclose(handle);
        return info.library.string() + ": the plugin does not provide ABI " + std::to_string(major) + "." +
               std::to_string(minor) + (info.abiVersion.empty() ? "" : " (it declares " + info.abiVersion + ")");
    }
    const auto* api = static_cast<const ObscuraApiV1*>(table);
    if (api->structSize < sizeof(ObscuraApiV1)) {
        dlclose(handle);
        return info.library.string() + ": function table smaller than ABI " + std::to_string(major) + "." +
               std::to_string(minor) + " requires";
    }
    return LoadedPlugin(info, handle, api);
}

fs::path executableDir() {
    std::error_code ec;
    fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::current_path() : self.parent_path();
}

fs::path defaultPluginDir() {
    std::error_code ec;
    fs::path dir = fs::weakly_canonical(executableDir() / ".." / OBSCURA_PLUGIN_RELDIR, ec);
    return ec ? executableDir() / ".." / OBSCURA_PLUGIN_RELDIR : dir;
}

}  // namespace obscura::harness
