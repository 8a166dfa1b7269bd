// Where the plugin's disk caches live (encoded textures, compiled pipelines): the folder a
// cache's own variable names, `off` turning that cache off; else $XDG_CACHE_HOME/obscura, else
// ~/.cache/obscura, as the XDG base directory specification puts a user's caches.
#pragma once

#include <filesystem>
#include <optional>

namespace obscura::delegate {

// nullopt: the cache is off, or there is no home folder to put it in.
std::optional<std::filesystem::path> cacheFolderFromEnvironment(const char* variable);

}  // namespace obscura::delegate
