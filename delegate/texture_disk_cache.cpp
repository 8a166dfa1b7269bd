#include "delegate/texture_disk_cache.h"

#include "gpu/replace_file.h"

#include <xxhash.h>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace obscura::delegate {

std::string TextureDiskCache::key(const std::string& file, const std::string& encoding) {
    return key(std::vector<std::string>{file}, encoding);
}

std::string TextureDiskCache::key(const std::vector<std::string>& files, const std::string& encoding) {
    // Streamed, so that one file's key is the hash of its bytes alone, as it always was.
    std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(), XXH3_freeState);
    XXH3_128bits_reset(state.get());
    for (const std::string& file : files) {
        const std::optional<std::vector<char>> content = gpu::readWholeFile(file);
        if (!content) return {};
        XXH3_128bits_update(state.get(), content->data(), content->size());
    }
    const XXH128_hash_t hash = XXH3_128bits_digest(state.get());
    char hex[33];
    std::snprintf(hex, sizeof(hex), "%016llx%016llx", static_cast<unsigned long long>(hash.high64),
                  static_cast<unsigned long long>(hash.low64));
    return encoding + "-" + hex;
}

std::optional<std::vector<std::byte>> TextureDiskCache::read(const std::string& key) const {
    if (!folder_ || key.empty()) return std::nullopt;
    const std::optional<std::vector<char>> content = gpu::readWholeFile(*folder_ / key);
    if (!content) return std::nullopt;
    std::vector<std::byte> bytes(content->size());
    std::transform(content->begin(), content->end(), bytes.begin(), [](char c) { return std::byte(c); });
    return bytes;
}

void TextureDiskCache::write(const std::string& key, const std::vector<std::byte>& bytes) const {
    if (!folder_ || key.empty()) return;
    gpu::replaceFile(*folder_ / key, bytes.data(), bytes.size());
}

}  // namespace obscura::delegate
