#include "harness/import/gltf_data_uris.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <optional>
#include <sstream>

namespace obscura::harness {
namespace {

bool isBase64Char(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
}

// RFC 4648, section 4: groups of four characters, '=' padding only at the end. Sets the decoded
// size, or returns the problem.
std::string base64Problem(const std::string& data, size_t& decoded) {
    size_t padding = 0;
    for (size_t i = 0; i < data.size(); ++i) {
        const char c = data[i];
        if (c == '=' && i + 2 >= data.size() && data.size() % 4 == 0) {
            ++padding;
            continue;
        }
        if (padding > 0 || !isBase64Char(c)) {
            const unsigned code = static_cast<unsigned char>(c);
            return "base64 data has " + (code >= 0x20 && code < 0x7F ? "'" + std::string(1, c) + "'" : "byte " + std::to_string(code)) +
                   " at offset " + std::to_string(i) + ", which base64 does not use";
        }
    }
    if (data.size() % 4 != 0)
        return "base64 data is " + std::to_string(data.size()) + " characters long, not a multiple of 4";
    decoded = data.size() / 4 * 3 - padding;
    return {};
}

// Where the text `needle` (a URI as written) starts in the file, as line:column.
std::string locationOf(const std::string& text, const std::string& needle) {
    const size_t at = text.find(needle);
    if (at == std::string::npos) return {};
    int line = 1, column = 1;
    for (size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') ++line, column = 1;
        else ++column;
    }
    return std::to_string(line) + ":" + std::to_string(column) + ": ";
}

}  // namespace

std::string checkGltfDataUris(const std::filesystem::path& file) {
    if (file.extension() != ".gltf") return {};
    std::ifstream in(file, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    const nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
    if (document.is_discarded() || !document.is_object()) return {};  // Assimp names the syntax error
    for (const char* section : {"buffers", "images"}) {
        const auto list = document.find(section);
        if (list == document.end() || !list->is_array()) continue;
        for (size_t i = 0; i < list->size(); ++i) {
            const nlohmann::json& item = (*list)[i];
            const auto uri = item.find("uri");
            if (!item.is_object() || uri == item.end() || !uri->is_string()) continue;
            const std::string& written = uri->get_ref<const std::string&>();
            if (!written.starts_with("data:")) continue;
            const std::string name = std::string(section) + "[" + std::to_string(i) + "].uri";
            const std::string where = file.string() + ":" + locationOf(text, written);
            const size_t comma = written.find(',');
            if (comma == std::string::npos || written.substr(0, comma).find(";base64") == std::string::npos)
                return where + name + ": a data URI without ';base64,' (glTF embeds only base64)";
            size_t decoded = 0;
            if (std::string problem = base64Problem(written.substr(comma + 1), decoded); !problem.empty())
                return where + name + ": " + problem;
            const auto length = item.find("byteLength");
            if (length != item.end() && length->is_number_unsigned() && decoded < length->get<size_t>())
                return where + name + ": base64 data holds " + std::to_string(decoded) + " bytes but byteLength is " +
                       std::to_string(length->get<size_t>());
        }
    }
    return {};
}

}  // namespace obscura::harness
