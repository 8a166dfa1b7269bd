// Encoded textures kept on disk, named by the content hash of their source file and the encoding:
// BC5 normal maps take seconds to encode well (the talk's exhaustive encoder took hours, Kaplanyan
// 2010, "3Dc encoder improvements, cont'd"), so each file is encoded once per content. The folder
// is cacheFolderFromEnvironment("OBSCURA_TEXTURE_CACHE") (delegate/cache_folder.h).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace obscura::delegate {

class TextureDiskCache {
public:
    explicit TextureDiskCache(std::optional<std::filesystem::path> folder) : folder_(std::move(folder)) {}

    // The hash of a source file's bytes, which names what is encoded from them.
    static std::string contentHash(std::string_view bytes);
    // The key of sources, by their contentHash, encoded as `encoding` (a name that changes with the
    // encoder): one file's hash, or several files' in this order (a UDIM set's tiles) hashed again.
    static std::string key(const std::vector<std::string>& contentHashes, const std::string& encoding);
    std::optional<std::vector<std::byte>> read(const std::string& key) const;
    // Written to a temporary name and renamed, so a reader never sees half a file; failures to
    // write are ignored (the cache only saves time).
    void write(const std::string& key, const std::vector<std::byte>& bytes) const;

private:
    std::optional<std::filesystem::path> folder_;
};

}  // namespace obscura::delegate
