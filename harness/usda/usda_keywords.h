// Words with a grammatical role in .usda text: list-op prefixes and statement keywords.
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <utility>

#include "harness/usda/list_op.h"
#include "harness/usda/usda_lexer.h"

namespace obscura::usda {

// The list edit a "prepend"/"append"/"add"/"delete"/"reorder" token introduces.
inline std::optional<ListOpKind> listOpKind(const Token& token) {
    constexpr std::array<std::pair<std::string_view, ListOpKind>, 5> kOps = {{
        {"prepend", ListOpKind::Prepend},
        {"append", ListOpKind::Append},
        {"add", ListOpKind::Add},
        {"delete", ListOpKind::Delete},
        {"reorder", ListOpKind::Reorder},
    }};
    for (const auto& [word, kind] : kOps)
        if (token.isWord(word)) return kind;
    return std::nullopt;
}

// Words that start statements or qualify declarations; they cannot be type names.
inline bool isKeyword(std::string_view word) {
    constexpr std::array<std::string_view, 16> kKeywords = {
        "def",    "over",    "class", "variantSet", "rel",  "custom", "uniform", "varying",
        "config", "prepend", "append", "add",       "delete", "reorder", "None",  "dictionary"};
    for (const std::string_view keyword : kKeywords)
        if (word == keyword) return true;
    return false;
}

}  // namespace obscura::usda
