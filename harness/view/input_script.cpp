#include "harness/view/input_script.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace obscura::harness::view {
namespace {

// The verbs and how many numbers each needs.
const std::map<std::string, size_t> kVerbs = {
    {"press", 2}, {"move", 2},   {"release", 2},        {"click", 2},       {"scroll", 1},
    {"key", 0},   {"aov", 0},    {"set", 0},            {"lens", 1},        {"frames", 1},
    {"wait-converged", 0},       {"wait-reload", 0},    {"screenshot", 0},  {"close", 0},
};

}  // namespace

bool ScriptEvent::has(const std::string& word) const { return std::find(words.begin(), words.end(), word) != words.end(); }

std::variant<std::vector<ScriptEvent>, std::string> readInputScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) return path + ": cannot read the script";
    return parseInputScript(in, path);
}

std::variant<std::vector<ScriptEvent>, std::string> parseInputScript(std::istream& in, const std::string& name) {
    std::vector<ScriptEvent> events;
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
        if (auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
        std::istringstream words(text);
        ScriptEvent e;
        e.line = line;
        if (!(words >> e.verb)) continue;
        auto verb = kVerbs.find(e.verb);
        if (verb == kVerbs.end()) return name + ":" + std::to_string(line) + ": unknown event '" + e.verb + "'";
        for (std::string w; words >> w;) {
            e.words.push_back(w);
            char* end = nullptr;
            double n = std::strtod(w.c_str(), &end);
            if (end && *end == '\0') e.numbers.push_back(n);
        }
        const bool needsWord = e.verb == "key" || e.verb == "aov" || e.verb == "set" || e.verb == "screenshot" ||
                               e.verb == "press" || e.verb == "release" || e.verb == "lens";
        if (e.numbers.size() < verb->second || (needsWord && e.words.empty()))
            return name + ":" + std::to_string(line) + ": '" + e.verb + "' needs more arguments";
        events.push_back(std::move(e));
    }
    return events;
}

}  // namespace obscura::harness::view
