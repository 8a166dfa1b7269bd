// Encoded textures kept on disk, named by the content hash of their source file and the encoding:
// BC5 normal maps take seconds to encode well (the talk's exhaustive encoder took hours, Kaplanyan
// 2010, "3Dc encoder improvements, cont'd"), so each file is encoded once per content. The folder
// is cacheFolderFromEnvironment("OBSCURA_TEXTURE_CACHE") (delegate/cache_folder.h).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace obscura::delegate {

class TextureDiskCache {
public:
    explicit TextureDiskCache(std::optional<std::filesystem::path> folder) : folder_(std::move(folder)) {}

    // The key of `file`'s content encoded as `encoding` (a name that changes with the encoder);
    // empty when the file cannot be read.
    static std::string key(const std::string& file, const std::string& encoding);
    // The key of several files' contents in this order (a UDIM set's tiles); for one file, its key.
    static std::string key(const std::vector<std::string>& files, const std::string& encoding);
    std::optional<std::vector<std::byte>> read(const std::string& key) const;
    // Written to a temporary name and renamed, so a reader never sees half a file; failures to
    // write are ignored (the cache only saves time).
    void write(const std::string& key, const std::vector<std::byte>& bytes) const;

private:
    std::optional<std::filesystem::path> folder_;
};

}  // namespace obscura::delegate
