// OpenUSD's plugInfo.json: JSON whose lines starting with '#' (after blanks) are comments, as the
// files usdGenSchema writes begin. Shared by plugin discovery and the variant fallbacks plugins
// declare, so both read every file OpenUSD reads.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>

namespace obscura::harness {

// Throws nlohmann::json::parse_error, whose byte index is the file's (comments are blanked, not
// removed); `//` and `/* */` comments are taken too.
nlohmann::json parsePlugInfoJson(const std::string& text);

// 1-based line and column of the 1-based byte index a parse error reports.
std::pair<int, int> plugInfoLineAndColumn(const std::string& text, size_t byte);

}  // namespace obscura::harness
