#include "delegate/texture_disk_cache.h"

#include "gpu/replace_file.h"

#include <xxhash.h>

#include <algorithm>
#include <cstdio>

namespace obscura::delegate {

std::string TextureDiskCache::contentHash(std::string_view bytes) {
    const XXH128_hash_t hash = XXH3_128bits(bytes.data(), bytes.size());
    char hex[33];
    std::snprintf(hex, sizeof(hex), "%016llx%016llx", static_cast<unsigned long long>(hash.high64),
                  static_cast<unsigned long long>(hash.low64));
    return hex;
}

std::string TextureDiskCache::key(const std::vector<std::string>& contentHashes, const std::string& encoding) {
    std::string hashes;
    for (const std::string& hash : contentHashes) hashes += hash;
    return encoding + "-" + (contentHashes.size() == 1 ? hashes : contentHash(hashes));
}

std::optional<std::vector<std::byte>> TextureDiskCache::read(const std::string& key) const {
    if (!folder_) return std::nullopt;
    const std::optional<std::vector<char>> content = gpu::readWholeFile(*folder_ / key);
    if (!content) return std::nullopt;
    std::vector<std::byte> bytes(content->size());
    std::transform(content->begin(), content->end(), bytes.begin(), [](char c) { return std::byte(c); });
    return bytes;
}

void TextureDiskCache::write(const std::string& key, const std::vector<std::byte>& bytes) const {
    if (!folder_) return;
    gpu::replaceFile(*folder_ / key, bytes.data(), bytes.size());
}

}  // namespace obscura::delegate
