#include "delegate/cache_folder.h"

#include <cstdlib>
#include <string>

namespace obscura::delegate {

std::optional<std::filesystem::path> cacheFolderFromEnvironment(const char* variable) {
    if (const char* folder = std::getenv(variable); folder && *folder) {
        if (std::string(folder) == "off") return std::nullopt;
        return std::filesystem::path(folder);
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "obscura";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "obscura";
    return std::nullopt;
}

}  // namespace obscura::delegate
