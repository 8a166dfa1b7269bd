#include "schemas/udim_pattern.h"

namespace obscura::schema {
namespace {

constexpr std::string_view kUdimToken = "<UDIM>";
constexpr size_t kDigits = 4;

}  // namespace

bool isUdimPattern(std::string_view path) { return path.find(kUdimToken) != std::string_view::npos; }

std::string udimTilePath(std::string_view pattern, int number) {
    std::string path(pattern);
    path.replace(path.find(kUdimToken), kUdimToken.size(), std::to_string(number));
    return path;
}

std::optional<int> udimTileNumber(std::string_view pattern, std::string_view path) {
    const size_t token = pattern.find(kUdimToken);
    if (token == std::string_view::npos || path.size() != pattern.size() - kUdimToken.size() + kDigits)
        return std::nullopt;
    const std::string_view before = pattern.substr(0, token), after = pattern.substr(token + kUdimToken.size());
    if (!path.starts_with(before) || !path.ends_with(after)) return std::nullopt;
    int number = 0;
    for (char c : path.substr(token, kDigits)) {
        if (c < '0' || c > '9') return std::nullopt;
        number = number * 10 + (c - '0');
    }
    if (number < kFirstUdimTile || number > kLastUdimTile) return std::nullopt;
    return number;
}

}  // namespace obscura::schema
