#include "harness/usda/sdf_path.h"

#include <algorithm>
#include <vector>

namespace obscura::usda::sdfpath {

size_t invalidUtf8At(std::string_view text) {
    const auto byte = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
    for (size_t i = 0; i < text.size();) {
        const unsigned char lead = byte(i);
        if (lead < 0x80) {
            ++i;
            continue;
        }
        // RFC 3629, section 4: the second byte's range depends on the lead byte.
        size_t length = 0;
        unsigned char low = 0x80, high = 0xBF;
        if (lead >= 0xC2 && lead <= 0xDF) length = 2;
        else if (lead >= 0xE0 && lead <= 0xEF) length = 3, low = lead == 0xE0 ? 0xA0 : 0x80, high = lead == 0xED ? 0x9F : 0xBF;
        else if (lead >= 0xF0 && lead <= 0xF4) length = 4, low = lead == 0xF0 ? 0x90 : 0x80, high = lead == 0xF4 ? 0x8F : 0xBF;
        else return i;
        if (i + length > text.size()) return i;
        if (byte(i + 1) < low || byte(i + 1) > high) return i;
        for (size_t k = 2; k < length; ++k)
            if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return i;
        i += length;
    }
    return std::string_view::npos;
}

bool isIdentifier(std::string_view name) {
    if (name.empty() || (name[0] >= '0' && name[0] <= '9') || invalidUtf8At(name) != std::string_view::npos) return false;
    for (const char c : name) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                        static_cast<unsigned char>(c) >= 0x80;
        if (!ok) return false;
    }
    return true;
}

std::string appendChild(std::string_view parent, std::string_view name) {
    std::string out(parent);
    if (out != "/") out += '/';
    out += name;
    return out;
}

std::string parentOf(std::string_view path) {
    const size_t slash = path.rfind('/');
    if (slash == std::string_view::npos || slash == 0) return "/";
    return std::string(path.substr(0, slash));
}

std::string nameOf(std::string_view path) {
    const size_t slash = path.rfind('/');
    return std::string(slash == std::string_view::npos ? path : path.substr(slash + 1));
}

int depthOf(std::string_view path) {
    int depth = 0;
    for (const char c : path) depth += (c == '/');
    return path == "/" ? 0 : depth;
}

std::string stripVariants(std::string_view path) {
    std::string out;
    int braces = 0;
    for (const char c : path) {
        if (c == '{') ++braces;
        if (braces == 0) out += c;
        if (c == '}' && braces > 0) --braces;
    }
    return out;
}

bool hasPrefix(std::string_view path, std::string_view prefix) {
    if (prefix == "/") return !path.empty() && path[0] == '/';
    if (path.substr(0, prefix.size()) != prefix) return false;
    if (path.size() == prefix.size()) return true;
    const char next = path[prefix.size()];
    return next == '/' || next == '.' || next == '{' || next == '[';
}

std::string replacePrefix(std::string_view path, std::string_view from, std::string_view to) {
    if (!hasPrefix(path, from)) return std::string(path);
    std::string_view rest = path.substr(from == "/" ? 1 : from.size());
    if (from == "/" && !rest.empty()) return appendChild(to, rest);
    return std::string(to) + std::string(rest);
}

std::optional<std::string> makeAbsolute(std::string_view path, std::string_view anchorPrim) {
    if (!path.empty() && path[0] == '/') return std::string(path);
    std::vector<std::string> parts;
    for (size_t start = 1; start < anchorPrim.size();) {
        const size_t end = std::min(anchorPrim.find('/', start), anchorPrim.size());
        parts.emplace_back(anchorPrim.substr(start, end - start));
        start = end + 1;
    }
    std::string property;
    size_t start = 0;
    while (start <= path.size()) {
        const size_t end = std::min(path.find('/', start), path.size());
        const std::string_view part = path.substr(start, end - start);
        const bool last = end == path.size();
        if (part == "..") {
            if (parts.empty()) return std::nullopt;
            parts.pop_back();
        } else if (last && !part.empty() && part[0] == '.') {
            property = part;  // ".prop": a property of the prim reached so far
        } else if (!part.empty() && part != ".") {
            parts.emplace_back(part);
        }
        start = end + 1;
    }
    std::string out;
    for (const std::string& part : parts) out += "/" + part;
    if (out.empty()) out = "/";
    return out + property;
}

}  // namespace obscura::usda::sdfpath
