#include "harness/import/usda_writer.h"

#include <charconv>
#include <cstdio>

namespace obscura::harness::importer {

namespace {

constexpr std::string_view kIndent = "    ";

template <class T>
std::string shortest(T value) {
    // -0 reads back as the same number but is noise in the text.
    if (value == 0) value = 0;
    // Shortest text that reads back to the same value; never locale-dependent.
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

bool isIdentifierChar(char c, bool first) {
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    return letter || (!first && c >= '0' && c <= '9');
}

// Invalid characters become '_' (a run of them one '_'); a leading digit gets a '_' before it.
std::string makeIdentifier(std::string_view name) {
    std::string out;
    for (const char c : name) {
        if (isIdentifierChar(c, false)) {
            out += c;
        } else if (out.empty() || out.back() != '_') {
            out += '_';
        }
    }
    if (!out.empty() && !isIdentifierChar(out.front(), true)) out.insert(out.begin(), '_');
    // A name that was nothing but invalid characters carries no meaning; the caller's fallback does.
    return out.find_first_not_of('_') == std::string::npos ? std::string() : out;
}

}  // namespace

UsdaWriter::UsdaWriter(const std::vector<std::string>& layerMetadata) {
    text_ = "#usda 1.0\n(\n";
    for (const std::string& item : layerMetadata) text_ += std::string(kIndent) + item + "\n";
    text_ += ")\n\n";
}

void UsdaWriter::line(std::string_view content) {
    for (int i = 0; i < depth_; ++i) text_ += kIndent;
    text_ += content;
    text_ += '\n';
}

void UsdaWriter::beginPrim(std::string_view type, std::string_view name, const std::vector<std::string>& metadata) {
    line("def " + std::string(type) + " " + stringLiteral(name) + (metadata.empty() ? "" : " ("));
    if (!metadata.empty()) {
        ++depth_;
        for (const std::string& item : metadata) line(item);
        --depth_;
        line(")");
    }
    line("{");
    ++depth_;
}

void UsdaWriter::endPrim() {
    --depth_;
    line("}");
}

void UsdaWriter::property(std::string_view declaration, std::string_view value) {
    line(std::string(declaration) + " = " + std::string(value));
}

void UsdaWriter::vertexProperty(std::string_view declaration, std::string_view value, size_t elementSize) {
    line(std::string(declaration) + " = " + std::string(value) + " (");
    ++depth_;
    if (elementSize != 1) line("elementSize = " + std::to_string(elementSize));
    line("interpolation = \"vertex\"");
    --depth_;
    line(")");
}

void UsdaWriter::declare(std::string_view declaration) { line(declaration); }

void UsdaWriter::timeSamples(std::string_view declaration, const std::vector<std::pair<double, std::string>>& samples) {
    line(std::string(declaration) + ".timeSamples = {");
    ++depth_;
    for (const auto& [time, value] : samples) line(number(time) + ": " + value + ",");
    --depth_;
    line("}");
}

std::string number(float value) { return shortest(value); }

std::string number(double value) { return shortest(value); }

std::string tuple(std::initializer_list<float> components) {
    std::string out = "(";
    for (const float c : components) out += (out.size() > 1 ? ", " : "") + number(c);
    return out + ")";
}

std::string matrix(const std::array<float, 16>& rowMajor) {
    std::string out = "(";
    for (size_t row = 0; row < 4; ++row) {
        const size_t i = row * 4;
        out += (row ? ", " : "") + tuple({rowMajor[i], rowMajor[i + 1], rowMajor[i + 2], rowMajor[i + 3]});
    }
    return out + ")";
}

std::string stringLiteral(std::string_view text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char escape[8];
            std::snprintf(escape, sizeof escape, "\\x%02x", static_cast<unsigned>(c));
            out += escape;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

std::string pathRef(std::string_view path) { return "<" + std::string(path) + ">"; }

std::optional<std::string> assetPath(std::string_view path) {
    if (path.find_first_of("\n\r") != std::string_view::npos) return std::nullopt;
    if (path.find('@') == std::string_view::npos) return "@" + std::string(path) + "@";
    std::string escaped;
    for (size_t i = 0; i < path.size(); ++i) {
        if (path.substr(i, 3) == "@@@") {
            escaped += "\\@@@";
            i += 2;
        } else {
            escaped += path[i];
        }
    }
    return "@@@" + escaped + "@@@";
}

std::string NameScope::claim(std::string_view name, std::string_view fallback) {
    std::string base = makeIdentifier(name);
    if (base.empty()) base = makeIdentifier(fallback);
    std::string candidate = base;
    for (int suffix = 1; used_.count(candidate); ++suffix) candidate = base + "_" + std::to_string(suffix);
    used_.insert(candidate);
    return candidate;
}

}  // namespace obscura::harness::importer
