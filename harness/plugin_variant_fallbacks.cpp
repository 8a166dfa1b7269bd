#include "harness/plugin_variant_fallbacks.h"

#include "harness/plug_info_json.h"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace obscura::harness {
namespace fs = std::filesystem;

namespace {

class Reader {
public:
    PluginVariantFallbacks out;

    // A plugInfo.json, or a folder's; OpenUSD passes over paths that hold none.
    void readEntry(const fs::path& entry) {
        std::error_code ec;
        const fs::path file = fs::is_directory(entry, ec) ? entry / "plugInfo.json" : entry;
        if (!fs::is_regular_file(file, ec) || !seen_.insert(fs::weakly_canonical(file, ec)).second) return;
        readFile(file);
    }

private:
    void warn(const fs::path& file, int line, int column, const std::string& message) {
        out.warnings.push_back({{file.string(), line, column}, message});
    }

    void readFile(const fs::path& file) {
        std::ifstream in(file);
        const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        if (!in && !in.eof()) {
            warn(file, 0, 0, "cannot be read; its plugins' variant fallbacks are ignored");
            return;
        }
        nlohmann::json doc;
        try {
            doc = parsePlugInfoJson(text);
        } catch (const nlohmann::json::parse_error& e) {
            const std::string what = e.what();
            const size_t detail = what.find(": ", what.find("column"));
            const auto [line, column] = plugInfoLineAndColumn(text, e.byte);
            warn(file, line, column,
                 "malformed plugInfo.json (" + (detail == std::string::npos ? what : what.substr(detail + 2)) +
                     "); its plugins' variant fallbacks are ignored");
            return;
        }
        if (!doc.is_object()) {
            warn(file, 1, 1, "plugInfo.json is not a JSON object; ignored");
            return;
        }
        if (const auto plugins = doc.find("Plugins"); plugins != doc.end() && plugins->is_array())
            for (size_t i = 0; i < plugins->size(); ++i) readPlugin((*plugins)[i], file, i);
        if (const auto includes = doc.find("Includes"); includes != doc.end() && includes->is_array())
            for (const auto& include : *includes)
                if (include.is_string()) readIncluded(file.parent_path() / include.get<std::string>());
    }

    void readPlugin(const nlohmann::json& plugin, const fs::path& file, size_t index) {
        if (!plugin.is_object() || !plugin.contains("Info") || !plugin["Info"].is_object()) return;
        const nlohmann::json& info = plugin["Info"];
        const auto fallbacks = info.find("UsdVariantFallbacks");
        if (fallbacks == info.end()) return;
        const std::string where = "Plugins[" + std::to_string(index) + "].Info.UsdVariantFallbacks";
        if (!fallbacks->is_object()) {
            warn(file, 0, 0, where + " is not a map of variant sets to variant names; ignored");
            return;
        }
        for (const auto& [set, variants] : fallbacks->items()) {
            const bool names = variants.is_array() && std::all_of(variants.begin(), variants.end(),
                                                                  [](const nlohmann::json& v) { return v.is_string(); });
            if (!names) {
                warn(file, 0, 0, where + "." + set + " is not a list of variant names; ignored");
                continue;
            }
            if (!variants.empty()) out.fallbacks[set] = variants.get<std::vector<std::string>>();
        }
    }

    // Includes name files or folders, with shell wildcards, as OpenUSD's plugInfo Includes do.
    void readIncluded(const fs::path& pattern) {
        glob_t matches{};
        if (glob(pattern.c_str(), 0, nullptr, &matches) == 0)
            for (size_t i = 0; i < matches.gl_pathc; ++i) readEntry(matches.gl_pathv[i]);
        globfree(&matches);
    }

    std::set<fs::path> seen_;  // a file reached twice (two entries, or Includes in a loop) is read once
};

}  // namespace

PluginVariantFallbacks readPluginVariantFallbacks(const std::string& searchPath) {
    Reader reader;
    std::stringstream entries(searchPath);
    std::string entry;
    while (std::getline(entries, entry, ':'))
        if (!entry.empty()) reader.readEntry(entry);
    return std::move(reader.out);
}

}  // namespace obscura::harness
