#include "delegate/texture_disk_cache.h"

#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace obscura::delegate {

std::optional<std::filesystem::path> TextureDiskCache::folderFromEnvironment() {
    if (const char* folder = std::getenv("OBSCURA_TEXTURE_CACHE"); folder && *folder) {
        if (std::string(folder) == "off") return std::nullopt;
        return std::filesystem::path(folder);
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "obscura";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "obscura";
    return std::nullopt;
}

std::string TextureDiskCache::key(const std::string& file, const std::string& encoding) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return {};
    const std::vector<char> content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const XXH128_hash_t hash = XXH3_128bits(content.data(), content.size());
    char hex[33];
    std::snprintf(hex, sizeof(hex), "%016llx%016llx", static_cast<unsigned long long>(hash.high64),
                  static_cast<unsigned long long>(hash.low64));
    return encoding + "-" + hex;
}

std::optional<std::vector<std::byte>> TextureDiskCache::read(const std::string& key) const {
    if (!folder_ || key.empty()) return std::nullopt;
    std::ifstream in(*folder_ / key, std::ios::binary);
    if (!in) return std::nullopt;
    const std::vector<char> content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::byte> bytes(content.size());
    std::transform(content.begin(), content.end(), bytes.begin(), [](char c) { return std::byte(c); });
    return bytes;
}

void TextureDiskCache::write(const std::string& key, const std::vector<std::byte>& bytes) const {
    if (!folder_ || key.empty()) return;
    std::error_code error;
    std::filesystem::create_directories(*folder_, error);
    const std::filesystem::path temporary = *folder_ / (key + ".tmp" + std::to_string(getpid()));
    {
        std::ofstream out(temporary, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!out) {
            std::filesystem::remove(temporary, error);
            return;
        }
    }
    std::filesystem::rename(temporary, *folder_ / key, error);
    if (error) std::filesystem::remove(temporary, error);
}

}  // namespace obscura::delegate
