#include "harness/plug_info_json.h"

#include <algorithm>

namespace obscura::harness {

nlohmann::json parsePlugInfoJson(const std::string& text) {
    std::string json = text;
    for (size_t start = 0; start < json.size();) {
        const size_t end = std::min(json.find('\n', start), json.size());
        const size_t first = json.find_first_not_of(" \t", start);
        if (first < end && json[first] == '#') std::fill(json.begin() + long(first), json.begin() + long(end), ' ');
        start = end + 1;
    }
    return nlohmann::json::parse(json, nullptr, true, true);
}

std::pair<int, int> plugInfoLineAndColumn(const std::string& text, size_t byte) {
    const size_t end = std::min(byte == 0 ? 0 : byte - 1, text.size());
    const size_t lineStart = end == 0 ? 0 : text.rfind('\n', end - 1) + 1;  // npos + 1 == 0: the first line
    return {1 + int(std::count(text.begin(), text.begin() + long(end), '\n')), 1 + int(end - lineStart)};
}

}  // namespace obscura::harness
