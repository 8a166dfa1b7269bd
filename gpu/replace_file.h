// Files that other processes may read while this one writes them (the disk caches): written to a
// temporary name beside the file and renamed over it, so a reader sees the old file or the new
// one, never half of one.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

namespace obscura::gpu {

// False when the file could not be written (the folder is made first); nothing is left behind.
bool replaceFile(const std::filesystem::path& file, const void* data, size_t size);
// The whole file, or nullopt when it cannot be opened.
std::optional<std::vector<char>> readWholeFile(const std::filesystem::path& file);

}  // namespace obscura::gpu
